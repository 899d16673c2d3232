#include "dermis/render/subsurface/coefficients.h"

#include <algorithm>
#include <map>
#include <memory>
#include <mutex>
#include <tuple>

#include "dermis/sss/study/albedo_inversion.h"
#include "dermis/sss/walk/albedo_inversion.h"

namespace dermis {

namespace {

// One table per (eta, g, exit), shared by every material of the process.
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

MediumAt medium_at(const SubsurfaceParams& p, const std::vector<Texture>* textures, Vec2 uv) {
  MediumAt m{p.sigma_a, p.sigma_s, p.reflectance, p.mfp};
  if (!textures || !p.textured()) return m;
  // Lengths are divided by scale, coefficients multiplied (pbrt-v4), as for constants.
  auto texture = [&](int index, float factor, float lo, float hi) {
    RGB v = evaluate_texture(*textures, index, uv) * factor;
    for (int c = 0; c < 3; ++c) v[c] = std::clamp(std::isfinite(v[c]) ? v[c] : lo, lo, hi);
    return v;
  };
  constexpr float kTiny = 1e-6f, kHuge = 1e30f;
  if (p.reflectance_texture >= 0) m.reflectance = texture(p.reflectance_texture, 1, 0, 1);
  if (p.mfp_texture >= 0) m.mfp = texture(p.mfp_texture, 1 / p.scale, kTiny, kHuge);
  if (p.sigma_a_texture >= 0) m.sigma_a = texture(p.sigma_a_texture, p.scale, 0, kHuge);
  if (p.sigma_s_texture >= 0) m.sigma_s = texture(p.sigma_s_texture, p.scale, 0, kHuge);
  return m;
}

const sss::AlbedoInversion* albedo_inversion_for(const SubsurfaceParams& p) {
  if (!p.reflectance || p.albedo_inversion_fit) return nullptr;
  // The half-space table of the walk's own boundary: the dielectric (Fresnel at entry
  // and at every exit); the diffuse boundary (refraction at entry, out at the first
  // crossing through the exit lobe); matched (eta = 1). A is per entering light under
  // diffuse incidence.
  using Boundary = SubsurfaceParams::Boundary;
  const double table_eta = p.boundary == Boundary::Matched ? 1.0 : p.eta;
  return &albedo_inversion(table_eta, p.g, p.boundary == Boundary::Diffuse);
}

Coefficients coefficients_from(const MediumAt& m, const sss::AlbedoInversion* table) {
  if (m.sigma_a) return {*m.sigma_a, *m.sigma_s};
  // sigma_t = 1 / mfp; alpha from the table, or van de Hulst's fit (g = 0,
  // index-matched) for comparison ("albedoinversion" "fit").
  Coefficients k;
  for (int c = 0; c < 3; ++c) {
    const double st = 1.0 / (*m.mfp)[c];
    const double A = (*m.reflectance)[c];
    const double alpha = table ? table->single_scattering_albedo(A) : sss::van_de_hulst_single_scattering_albedo(A);
    k.sigma_s[c] = float(alpha * st);
    k.sigma_a[c] = float((1 - alpha) * st);
  }
  return k;
}

AlbedoAndMfp albedo_and_mfp(const MediumAt& m, float g) {
  if (m.reflectance) return {*m.reflectance, *m.mfp};
  AlbedoAndMfp r;
  for (int c = 0; c < 3; ++c) {
    double ss = (*m.sigma_s)[c] * (1 - g), st = (*m.sigma_a)[c] + ss;
    r.mfp[c] = float(1 / st);
    r.albedo[c] = float(sss::surface_albedo_index_matched(ss / st));  // Chandrasekhar 1950 (METHODS.md sec. 6)
  }
  return r;
}

}  // namespace dermis
