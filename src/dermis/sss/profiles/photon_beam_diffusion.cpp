#include "dermis/sss/profiles/photon_beam_diffusion.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "dermis/core/fresnel.h"
#include "dermis/core/henyey_greenstein.h"
#include "dermis/core/vec.h"
#include "dermis/sss/profiles/quadrature.h"

namespace dermis::sss {
namespace {

// int_0^inf f(z) dz for an f that decays like e^{-z / length} (f includes it) and may
// peak at depths of order `near` (the distance r of the surface point: the beam's nearest
// part): z = c (e^w - 1), c = min(near, length), makes both scales a few units of w wide;
// 16-point Gauss-Legendre on pieces of w at most 3 long, up to z = 40 length (e^-40 ~ 4e-18).
template <class F>
double integrate_depth(const F& f, double near, double length) {
  const double c = std::max(std::min(near, length), 1e-12 * length);
  const double w_max = std::log1p(40 * length / c);
  const int pieces = std::max(1, int(std::ceil(w_max / 3)));
  const double step = w_max / pieces;
  auto in_w = [&](double w) {
    const double e = std::exp(w);
    return f(c * (e - 1)) * c * e;  // dz = c e^w dw
  };
  double sum = 0;
  for (int i = 0; i < pieces; ++i) sum += gauss_legendre_16(in_w, i * step, (i + 1) * step);
  return sum;
}

}  // namespace

PhotonBeamDiffusion::PhotonBeamDiffusion(double rho, double g, double eta) : rho_(rho), g_(g), eta_(eta) {
  if (!(rho >= 0 && rho <= 1)) throw std::invalid_argument("photon beam diffusion: rho must lie in [0, 1]");
  if (!(g > -1 && g < 1)) throw std::invalid_argument("photon beam diffusion: g must lie in (-1, 1)");
  if (!(eta > 0) || !std::isfinite(eta)) throw std::invalid_argument("photon beam diffusion: eta must be positive");
  // sigma_t = 1: sigma_s = rho, sigma_a = 1 - rho.
  sigma_a_ = 1 - rho;
  const double sigma_sp = rho * (1 - g);  // similarity: sigma_s' = sigma_s (1 - g)
  sigma_tp_ = sigma_a_ + sigma_sp;
  rho_p_ = sigma_sp / sigma_tp_;
  d_g_ = (2 * sigma_a_ + sigma_sp) / (3 * sigma_tp_ * sigma_tp_);  // Grosjean's D (PBR 3rd ed. eq. 15.24)
  sigma_tr_ = std::sqrt(sigma_a_ / d_g_);                          // sigma_tr = sqrt(sigma_a / D)
  // The Fresnel moments of light inside reaching the boundary (relative index 1 / eta).
  const double fm1 = fresnel_moment(1, 1 / eta), fm2 = fresnel_moment(2, 1 / eta);
  z_e_ = -2 * d_g_ * (1 + 3 * fm2) / (1 - 2 * fm1);  // extrapolated boundary (d'Eon & Irving 2011; PBR eq. 15.26)
  c_phi_ = 0.25 * (1 - 2 * fm1);                     // exitance factors (PBR eqs. 15.28, 15.29)
  c_e_ = 0.5 * (1 - 3 * fm2);
  t_crit_per_r_ = std::sqrt(std::max(0.0, eta * eta - 1));
}

double PhotonBeamDiffusion::dipole_exitance(double z_r, double r) const {
  const double z_v = -z_r + 2 * z_e_;  // the virtual source, mirrored in the extrapolated boundary
  const double d_r = std::sqrt(r * r + z_r * z_r), d_v = std::sqrt(r * r + z_v * z_v);
  const double e_r = std::exp(-sigma_tr_ * d_r), e_v = std::exp(-sigma_tr_ * d_v);
  // Fluence of the dipole (PBR eq. 15.27) and its flux through the surface (eq. 15.29's E_n).
  const double phi = (e_r / d_r - e_v / d_v) / (4 * kPiD * d_g_);
  const double e_n =
      (z_r * (1 + sigma_tr_ * d_r) * e_r / (d_r * d_r * d_r) - z_v * (1 + sigma_tr_ * d_v) * e_v / (d_v * d_v * d_v)) /
      (4 * kPiD);
  return c_phi_ * phi + c_e_ * e_n;
}

double PhotonBeamDiffusion::plane_exitance(double z_r) const {
  // int e^{-s d}/d dA = 2 pi e^{-s |z|} / s and int z (1 + s d) e^{-s d} / d^3 dA = 2 pi sign(z) e^{-s |z|}.
  const double z_v = -z_r + 2 * z_e_;
  const double s = sigma_tr_;
  const double e_r = std::exp(-s * std::abs(z_r)), e_v = std::exp(-s * std::abs(z_v));
  const double phi = s > 0 ? (e_r - e_v) / (2 * d_g_ * s) : (std::abs(z_v) - std::abs(z_r)) / (2 * d_g_);
  const double e_n = 0.5 * ((z_r > 0 ? 1 : -1) * e_r - (z_v > 0 ? 1 : -1) * e_v);
  return c_phi_ * phi + c_e_ * e_n;
}

double PhotonBeamDiffusion::multiple(double r) const {
  if (!(r > 0) || rho_p_ <= 0) return 0;
  // E_d(r) = int_0^inf sigma_t' e^{-sigma_t' z} rho'^2 kappa(z) E(z, r) dz (Habel et al. 2013,
  // eq. 12 as in PBR sec. 15.5.4), kappa = 1 - e^{-2 sigma_t' (d_r + z)} (their eq. 16).
  auto integrand = [&](double z) {
    const double d_r = std::sqrt(r * r + z * z);
    const double kappa = -std::expm1(-2 * sigma_tp_ * (d_r + z));
    return sigma_tp_ * std::exp(-sigma_tp_ * z) * rho_p_ * rho_p_ * kappa * dipole_exitance(z, r);
  };
  return integrate_depth(integrand, r, 1 / sigma_tp_);
}

double PhotonBeamDiffusion::single(double r) const {
  // Beyond 40 mean free paths the path to the point alone attenuates by e^-40 ~ 4e-18.
  if (!(r > 0) || rho_ <= 0 || r > 40) return 0;
  // E_ss(r) = int_{t_c}^inf sigma_s e^{-t} e^{-d} p(cos) T(cos) cos / d^2 dt (PBR eq. 15.31,
  // sigma_t = 1): scattered at depth t on the beam toward the surface point at distance
  // d = sqrt(r^2 + t^2), leaving at cos = t / d through the boundary (transmittance T from
  // inside); t_c = r sqrt(eta^2 - 1): shallower points meet the surface beyond the critical angle.
  const double t_c = r * t_crit_per_r_;
  auto integrand = [&](double s) {
    const double t = t_c + s, d = std::sqrt(r * r + t * t), cos_o = t / d;
    // The beam travels down, the scattered light up toward the point: cos of the
    // scattering angle is -t / d (core/henyey_greenstein.h's convention).
    const double phase = henyey_greenstein(-cos_o, g_);
    const double transmittance = 1 - fresnel_dielectric(cos_o, 1 / eta_);
    return rho_ * std::exp(-(t + d)) * phase * transmittance * cos_o / (d * d);
  };
  return integrate_depth(integrand, std::max(r, t_c), 1.0);
}

ProfileFamily photon_beam_family(double g, double eta) {
  PhotonBeamDiffusion(0.5, g, eta);  // validates g and eta now rather than per node
  return [g, eta](double rho) {
    const PhotonBeamDiffusion p(rho, g, eta);
    return RadialFunction([p](double r) { return p.eval(r); });
  };
}

ProfileTableOptions photon_beam_table_options() {
  ProfileTableOptions o;
  constexpr int kNodes = 64;
  const double lo = std::log(1e-3 / (1 - 1e-3)), hi = std::log((1 - 1e-5) / 1e-5);
  o.albedos.resize(kNodes);
  for (int i = 0; i < kNodes; ++i) o.albedos[i] = 1 / (1 + std::exp(-(lo + (hi - lo) * i / (kNodes - 1))));
  o.radial_nodes = 256;
  return o;
}

}  // namespace dermis::sss
