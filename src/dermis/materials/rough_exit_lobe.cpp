#include "dermis/materials/rough_exit_lobe.h"

#include <algorithm>
#include <cmath>

#include "dermis/core/fresnel.h"
#include "dermis/core/microfacet.h"
#include "dermis/core/vec.h"
#include "dermis/materials/microfacet_bsdf.h"

namespace dermis {

namespace {

constexpr int kTableResolution = 64;  // k of the quadrature at each node
// Azimuths of wo over a quarter turn: the distribution is even in x and in y, so T(phi)
// has the symmetry of the rectangle and this midpoint rule equals 16 over the whole turn.
constexpr int kAnisotropicAzimuths = 4;

}  // namespace

float RoughExitTable::at(float mu) const {
  if (!(mu > 0)) return 0;
  const float x = std::min(mu, 1.0f) * (kNodes - 1);
  const int i = std::min(int(x), kNodes - 2);
  const float t = x - float(i);
  return transmittance[i] * (1 - t) + transmittance[i + 1] * t;
}

double rough_dielectric_transmittance(float eta, float alpha_x, float alpha_y, float mu, int k) {
  const TrowbridgeReitz d(alpha_x, alpha_y);
  mu = std::clamp(mu, 1e-4f, 1.0f);  // at mu = 0 the sampler is undefined: the node takes mu = 1e-4
  const float sin_theta = std::sqrt(std::max(0.0f, 1 - mu * mu));
  const int n_phi = alpha_x == alpha_y ? 1 : kAnisotropicAzimuths;
  double sum = 0;
  for (int a = 0; a < n_phi; ++a) {
    const float phi = 0.5f * kPi * (a + 0.5f) / n_phi;
    const Vec3 wo(sin_theta * std::cos(phi), sin_theta * std::sin(phi), mu);
    for (int i = 0; i < k; ++i) {
      // The sampler's radial coordinate u1 (the disk radius is sqrt(u1), the lift onto the
      // hemisphere sqrt(1 - r^2)) through u1 = t^2 (3 - 2 t), whose derivative 6 t (1 - t)
      // vanishes at both ends: the square roots there become smooth in t, and the
      // midpoint rule in t converges as h^2 (in u1 it converged as h).
      const double t = (i + 0.5) / k, u1 = t * t * (3 - 2 * t), du1 = 6 * t * (1 - t);
      for (int j = 0; j < k; ++j) {
        // T = integral of f_t |cos wi| dwi through the change of variables u -> m -> wi of
        // the visible-normal sampler: density D_wo(m) (Heitz 2018, eq. 1) times the
        // refraction Jacobian (Walter et al. 2007, eq. 17); eval's 1/eta^2 taken out.
        const Vec3 m = d.sample_visible(wo, {float(u1), (j + 0.5f) / k});
        const auto wi = refract(wo, m, eta);
        if (!wi || wi->z >= 0) continue;  // refracted back up: the model loses it
        const float density = d.visible_pdf(wo, m) * refraction_jacobian(wo, *wi, m, eta);
        if (!(density > 0)) continue;
        sum += double(rough_dielectric_eval(d, eta, wo, *wi)) * eta * eta / density * du1;
      }
    }
  }
  return sum / (double(k) * k * n_phi);
}

namespace {

// c of a table whose nodes are filled in.
void set_norm(RoughExitTable& t) {
  constexpr int n = RoughExitTable::kNodes;
  // 2 integral of the piecewise-linear T times mu: on [a, b], h (Ta (2a + b) + Tb (a + 2b)) / 6.
  double c = 0;
  const double h = 1.0 / (n - 1);
  for (int i = 0; i + 1 < n; ++i) {
    const double a = i * h, b = (i + 1) * h;
    c += h * (double(t.transmittance[i]) * (2 * a + b) + double(t.transmittance[i + 1]) * (a + 2 * b)) / 6;
  }
  t.norm = float(2 * c);
}

}  // namespace

RoughExitTable make_rough_exit_table(float eta, float alpha_x, float alpha_y) {
  RoughExitTable t;
  constexpr int n = RoughExitTable::kNodes;
  for (int i = 0; i < n; ++i)
    t.transmittance[i] =
        float(rough_dielectric_transmittance(eta, alpha_x, alpha_y, float(i) / (n - 1), kTableResolution));
  set_norm(t);
  return t;
}

RoughExitTable make_smooth_exit_table(float eta) {
  RoughExitTable t;
  constexpr int n = RoughExitTable::kNodes;
  for (int i = 0; i < n; ++i) t.transmittance[i] = 1 - fresnel_dielectric(std::max(float(i) / (n - 1), 1e-4f), eta);
  set_norm(t);
  return t;
}

RoughExitTables::RoughExitTables(float eta) {
  tables_.reserve(kAlphaNodes);
  tables_.push_back(make_smooth_exit_table(eta));
  for (int k = 1; k < kAlphaNodes; ++k) {
    const float alpha = node_alpha(k);
    tables_.push_back(make_rough_exit_table(eta, alpha, alpha));
  }
}

float RoughExitTables::node_alpha(int k) {
  const float t = float(k) / (kAlphaNodes - 1);
  return t * t;
}

void RoughExitTables::at(float alpha, RoughExitTable& out) const {
  const float x = std::sqrt(std::clamp(alpha, 0.0f, 1.0f)) * (kAlphaNodes - 1);
  const int k = std::min(int(x), kAlphaNodes - 2);
  const float w = x - float(k);
  const RoughExitTable &a = tables_[std::size_t(k)], &b = tables_[std::size_t(k) + 1];
  for (int i = 0; i < RoughExitTable::kNodes; ++i)
    out.transmittance[i] = a.transmittance[i] * (1 - w) + b.transmittance[i] * w;
  out.norm = a.norm * (1 - w) + b.norm * w;  // c is linear in T: the blend's own c
}

}  // namespace dermis
