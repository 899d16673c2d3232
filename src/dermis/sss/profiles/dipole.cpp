#include "dermis/sss/profiles/dipole.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "dermis/sss/profiles/gaussian.h"

namespace dermis::sss {
namespace {

void check_eta(double eta) {
  if (!(eta >= 1 && eta <= 4))
    throw std::invalid_argument(
        "dipole: the index of refraction must lie in [1, 4], where the fit of F_dr holds (got " + std::to_string(eta) +
        ")");
}

constexpr int kInverseCdfSize = 513;

// Jensen et al. 2001, eq. 4, divided by alpha' (so that a zero albedo keeps a shape).
double dipole_shape(double r, double sigma_tr, double z_r, double z_v) {
  const double dr = std::sqrt(r * r + z_r * z_r), dv = std::sqrt(r * r + z_v * z_v);
  return (z_r * (1 + sigma_tr * dr) * std::exp(-sigma_tr * dr) / (dr * dr * dr) +
          z_v * (1 + sigma_tr * dv) * std::exp(-sigma_tr * dv) / (dv * dv * dv)) /
         (4 * kPiD);
}

// int_0^r 2 pi r' shape dr' = (1/2) sum_{z in z_r, z_v} (e^{-sigma_tr z} - z e^{-sigma_tr d} / d), d = sqrt(r^2 + z^2),
// since d/dd (-e^{-s d}/d) = (1 + s d) e^{-s d} / d^2 and r dr = d dd (docs/profiles.md).
double dipole_shape_energy(double r, double sigma_tr, double z_r, double z_v) {
  const double dr = std::sqrt(r * r + z_r * z_r), dv = std::sqrt(r * r + z_v * z_v);
  return 0.5 * (std::exp(-sigma_tr * z_r) - z_r * std::exp(-sigma_tr * dr) / dr + std::exp(-sigma_tr * z_v) -
                z_v * std::exp(-sigma_tr * dv) / dv);
}

}  // namespace

double dipole_fresnel_diffuse_reflectance(double eta) {
  check_eta(eta);
  return -1.440 / (eta * eta) + 0.710 / eta + 0.668 + 0.0636 * eta;  // Jensen et al. 2001, sec. 2.4
}

double dipole_boundary_a(double eta) {
  const double fdr = dipole_fresnel_diffuse_reflectance(eta);
  return (1 + fdr) / (1 - fdr);  // Jensen et al. 2001, sec. 2.4
}

double dipole_total_reflectance(double alpha, double eta) {
  const double a_b = dipole_boundary_a(eta);
  const double t = std::sqrt(3 * (1 - alpha));
  return 0.5 * alpha * (1 + std::exp(-4.0 / 3.0 * a_b * t)) * std::exp(-t);  // Jensen & Buehler 2002, eq. 3
}

double dipole_reduced_albedo_from_reflectance(double reflectance, double eta) {
  if (!(reflectance >= 0 && reflectance <= 1))
    throw std::invalid_argument("dipole: the surface albedo must lie in [0, 1] (got " + std::to_string(reflectance) +
                                ")");
  check_eta(eta);
  double lo = 0, hi = 1;  // R_d(0) = 0, R_d(1) = 1, increasing in between
  while (hi - lo > 1e-13) {
    const double mid = 0.5 * (lo + hi);
    (dipole_total_reflectance(mid, eta) < reflectance ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

DipoleProfile DipoleProfile::from_coefficients(double sigma_a, double sigma_s, double g, double eta,
                                               double kept_fraction) {
  if (!(sigma_a >= 0) || !(sigma_s >= 0) || !std::isfinite(sigma_a) || !std::isfinite(sigma_s))
    throw std::invalid_argument("dipole: sigma_a and sigma_s must be finite and >= 0 (got " + std::to_string(sigma_a) +
                                ", " + std::to_string(sigma_s) + ")");
  if (!(g > -1 && g < 1))
    throw std::invalid_argument("dipole: the mean cosine g must lie in (-1, 1) (got " + std::to_string(g) + ")");
  const double sigma_s_reduced = sigma_s * (1 - g);
  const double sigma_t_reduced = sigma_a + sigma_s_reduced;  // Jensen et al. 2001, sec. 2.4
  if (!(sigma_t_reduced > 0)) throw std::invalid_argument("dipole: sigma_a + sigma_s (1 - g) must be positive");
  return DipoleProfile(sigma_s_reduced / sigma_t_reduced, sigma_t_reduced, eta, kept_fraction);
}

DipoleProfile DipoleProfile::from_albedo(double albedo, double mean_free_path, double eta, double kept_fraction) {
  if (!(albedo > 0 && albedo <= 1))
    throw std::invalid_argument("dipole: the surface albedo must lie in (0, 1] (got " + std::to_string(albedo) + ")");
  if (!(mean_free_path > 0) || !std::isfinite(mean_free_path))
    throw std::invalid_argument("dipole: the mean free path must be positive (got " + std::to_string(mean_free_path) +
                                ")");
  return DipoleProfile(dipole_reduced_albedo_from_reflectance(albedo, eta), 1 / mean_free_path, eta, kept_fraction);
}

DipoleProfile::DipoleProfile(double alpha, double sigma_t_reduced, double eta, double kept_fraction)
    : alpha_(alpha), sigma_t_reduced_(sigma_t_reduced), eta_(eta), kept_(kept_fraction) {
  GaussianProfile::check_fraction(kept_fraction);
  // Jensen et al. 2001, sec. 2.4 and eq. 4: sigma_tr, z_r = 1 / sigma'_t, z_v = z_r (1 + 4 A_b / 3).
  const double sigma_a = sigma_t_reduced * (1 - alpha);
  sigma_tr_ = std::sqrt(3 * sigma_a * sigma_t_reduced);
  z_r_ = 1 / sigma_t_reduced;
  z_v_ = z_r_ * (1 + 4.0 / 3.0 * dipole_boundary_a(eta));
  albedo_ = 0.5 * alpha_ * (std::exp(-sigma_tr_ * z_r_) + std::exp(-sigma_tr_ * z_v_));
  r_max_ = r_max(kept_fraction);
  // Tabulated inverse CDF of the truncated distribution (the Newton start of sample_radius).
  auto table = std::make_shared<std::vector<double>>(kInverseCdfSize);
  (*table)[0] = 0;
  (*table)[kInverseCdfSize - 1] = r_max_;
  truncated_shape_energy_ = dipole_shape_energy(r_max_, sigma_tr_, z_r_, z_v_);
  const double total = truncated_shape_energy_;
  for (int i = 1; i + 1 < kInverseCdfSize; ++i)
    (*table)[i] = solve_energy(total * i / (kInverseCdfSize - 1), (*table)[i - 1], r_max_, -1);
  inverse_cdf_ = std::move(table);
}

double DipoleProfile::eval(double r) const { return alpha_ * dipole_shape(r, sigma_tr_, z_r_, z_v_); }

double DipoleProfile::energy_within(double r) const { return alpha_ * dipole_shape_energy(r, sigma_tr_, z_r_, z_v_); }

double DipoleProfile::solve_energy(double target_shape_energy, double lo, double hi, double start) const {
  double r = start > lo && start < hi ? start : 0.5 * (lo + hi);
  for (int it = 0; it < 200; ++it) {
    const double f = dipole_shape_energy(r, sigma_tr_, z_r_, z_v_) - target_shape_energy;
    if (f == 0) return r;
    if (f < 0)
      lo = r;
    else
      hi = r;
    const double df = 2 * kPiD * r * dipole_shape(r, sigma_tr_, z_r_, z_v_);
    double next = df > 0 ? r - f / df : 0.5 * (lo + hi);
    if (!(next >= lo && next <= hi)) next = 0.5 * (lo + hi);
    if (std::abs(next - r) <= 1e-13 * r_max_ || hi - lo <= 1e-14 * hi) return next;
    r = next;
  }
  return r;
}

double DipoleProfile::r_max(double energy_fraction) const {
  GaussianProfile::check_fraction(energy_fraction);
  const double total = 0.5 * (std::exp(-sigma_tr_ * z_r_) + std::exp(-sigma_tr_ * z_v_));
  const double target = energy_fraction * total;
  double hi = z_v_;
  while (dipole_shape_energy(hi, sigma_tr_, z_r_, z_v_) < target) hi *= 2;
  double lo = 0;
  while (hi - lo > 1e-14 * hi) {
    const double mid = 0.5 * (lo + hi);
    (dipole_shape_energy(mid, sigma_tr_, z_r_, z_v_) < target ? lo : hi) = mid;
  }
  return hi;
}

double DipoleProfile::sample_radius(double xi) const {
  const std::vector<double>& table = *inverse_cdf_;
  const double total = truncated_shape_energy_;
  const double x = std::clamp(xi, 0.0, 1.0) * (kInverseCdfSize - 1);
  const int i = std::min(int(x), kInverseCdfSize - 2);
  const double start = table[i] + (x - i) * (table[i + 1] - table[i]);
  return solve_energy(xi * total, table[i], table[i + 1], start);
}

double DipoleProfile::pdf_radius(double r) const {
  if (r < 0 || r > r_max_) return 0;
  const double total = truncated_shape_energy_;
  return 2 * kPiD * r * dipole_shape(r, sigma_tr_, z_r_, z_v_) / total;
}

}  // namespace dermis::sss
