// The exit lobe Sw of the subsurface methods through a rough boundary. Light diffusing
// inside an object leaves toward wi in proportion to the boundary's transmittance from
// outside at wi (reciprocity of the BTDF, Veach 1997, sec. 5.2, with the 1/eta^2
// radiance factor taken out): for the smooth boundary 1 - Fr(cos theta, eta), which
// gives the normalised-Fresnel lobe of bsdf.h; for the rough dielectric
// (microfacet_bsdf.h) its directional transmittance
//   T(mu; alpha, eta) = eta^2 integral over the inside of f_t(wo, wi) |cos wi| dwi,
// mu = cos theta of wo, tabulated once per material by quadrature. Then
//   Sw(wi) = T(cos theta_i) / (c pi),  c = 2 integral_0^1 T(mu) mu dmu,
// with c from the same (interpolated) table, so that Sw integrates to one against cos.
// T is the rough dielectric's own transmittance: 1 - E_r (E_r its directional
// reflectance) less the energy its single-scattering microfacet model loses; as
// alpha -> 0 it tends to 1 - Fr. Anisotropic roughness: T averaged over the azimuth of
// wo (the exit lobe is isotropic).
#pragma once

#include <array>
#include <vector>

namespace dermis {

struct RoughExitTable {
  static constexpr int kNodes = 65;  // mu_i = i / 64, i = 0 .. 64
  std::array<float, kNodes> transmittance{};
  float norm = 1;  // c: 2 integral of the piecewise-linear T(mu) times mu over [0, 1], exact

  // T(mu), linear between the nodes (node 0 holds T(1e-4)); 0 for mu <= 0.
  float at(float mu) const;
};

// The rough dielectric's directional transmittance from outside (eta: inside over
// outside) at cos theta = mu, by the midpoint rule on a k x k grid of the visible-normal
// sampler's unit square (its radial coordinate smoothed, see the .cpp), times 4 azimuths
// of wo over a quarter turn when anisotropic (by symmetry, 16 over the whole turn).
// Exposed for tests.
double rough_dielectric_transmittance(float eta, float alpha_x, float alpha_y, float mu, int k);

// The table of a material: T at every node (k = 64), and c.
RoughExitTable make_rough_exit_table(float eta, float alpha_x, float alpha_y);

// The smooth boundary's T = 1 - Fr(mu, eta) at the nodes (node 0 at mu = 1e-4), and the
// c of that piecewise-linear T (within 1e-4 of the exact smooth lobe's).
RoughExitTable make_smooth_exit_table(float eta);

// A textured (isotropic) roughness: tables at alpha = (k / 16)^2, k = 0 .. 16 (k = 0 the
// smooth table; nodes uniform in sqrt(alpha), because T changes fastest in alpha near
// 0, at grazing mu), blended linearly in sqrt(alpha) at each exit point. Blending tables
// blends their c as well (c is linear in T), so the blend integrates to one as each node
// does. About one second to make (16 rough tables).
class RoughExitTables {
 public:
  static constexpr int kAlphaNodes = 17;
  explicit RoughExitTables(float eta);
  // The table at `alpha` (clamped to [0, 1]), written into `out` (no allocation).
  void at(float alpha, RoughExitTable& out) const;
  const RoughExitTable& node(int k) const { return tables_[std::size_t(k)]; }
  static float node_alpha(int k);  // (k / 16)^2

 private:
  std::vector<RoughExitTable> tables_;
};

}  // namespace dermis
