#include "dermis/render/subsurface/coefficients.h"

#include <map>
#include <memory>
#include <mutex>
#include <tuple>

#include "dermis/sss/study/albedo_inversion.h"
#include "dermis/sss/walk/albedo_inversion.h"

namespace dermis {

namespace {

// The exact albedo inversion of the random walk, one table per (eta, g, exit), shared
// by every material of the process.
const sss::AlbedoInversion& albedo_inversion(double eta, double g, bool exit_matched) {
  static std::mutex mutex;
  static std::map<std::tuple<double, double, bool>, std::unique_ptr<sss::AlbedoInversion>> tables;
  std::lock_guard<std::mutex> lock(mutex);
  auto& t = tables[{eta, g, exit_matched}];
  if (!t) {
    sss::AlbedoTableConfig config;
    config.eta = eta;
    config.g = g;
    config.exit_matched = exit_matched;
    t = std::make_unique<sss::AlbedoInversion>(config);
  }
  return *t;
}

}  // namespace

Coefficients resolve_coefficients(const SubsurfaceParams& p) {
  if (p.sigma_a) return {*p.sigma_a, *p.sigma_s};
  // From (A, mfp): sigma_t = 1 / mfp and alpha from the half-space table of the walk's
  // own boundary: the dielectric (Fresnel at entry and at every exit); the diffuse
  // boundary (refraction at entry, out at the first crossing through the exit lobe);
  // matched (eta = 1). A is per entering light under diffuse incidence.
  // "albedoinversion" "fit": van de Hulst's fit instead (g = 0, index-matched), for comparison.
  using Boundary = SubsurfaceParams::Boundary;
  const double table_eta = p.boundary == Boundary::Matched ? 1.0 : p.eta;
  const bool exit_matched = p.boundary == Boundary::Diffuse;
  const sss::AlbedoInversion* inv =
      p.albedo_inversion_fit ? nullptr : &albedo_inversion(table_eta, p.g, exit_matched);
  Coefficients k;
  for (int c = 0; c < 3; ++c) {
    double st = 1.0 / (*p.mfp)[c];
    double A = (*p.reflectance)[c];
    double alpha = inv ? inv->single_scattering_albedo(A) : sss::van_de_hulst_single_scattering_albedo(A);
    k.sigma_s[c] = float(alpha * st);
    k.sigma_a[c] = float((1 - alpha) * st);
  }
  return k;
}

AlbedoAndMfp albedo_and_mfp(const SubsurfaceParams& p) {
  if (p.reflectance) return {*p.reflectance, *p.mfp};
  AlbedoAndMfp r;
  for (int c = 0; c < 3; ++c) {
    double ss = (*p.sigma_s)[c] * (1 - p.g), st = (*p.sigma_a)[c] + ss;
    r.mfp[c] = float(1 / st);
    r.albedo[c] = float(sss::surface_albedo_index_matched(ss / st));  // Chandrasekhar 1950 (METHODS.md sec. 6)
  }
  return r;
}

}  // namespace dermis
