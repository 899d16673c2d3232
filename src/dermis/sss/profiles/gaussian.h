// One Gaussian radial profile (King et al. 2013, the Gaussian of d'Eon & Luebke 2007),
// truncated for sampling at R_m = sqrt(12.46 v). See docs/profiles.md and METHODS.md 1.1.
#pragma once

#include <cmath>
#include <stdexcept>
#include <string>

namespace dermis::sss {

inline constexpr double kPiD = 3.14159265358979323846;

// R_m^2 / (2v) for R_m = sqrt(12.46 v): the truncation keeps 1 - e^{-6.23} = 99.80%
// of the energy (METHODS 1.1, correcting the seed's R_m = sqrt(v / 12.46)).
inline constexpr double kGaussianTruncationExponent = 12.46 / 2;

// Normalised 2D Gaussian G(v, r) = exp(-r^2 / (2v)) / (2 pi v); int G 2 pi r dr = 1
// (d'Eon & Luebke 2007, GPU Gems 3 ch. 14, eq. 14-3; METHODS 1.1).
inline double gaussian_2d(double variance, double r) {
  return std::exp(-r * r / (2 * variance)) / (2 * kPiD * variance);
}

// R(r) = weight * G(v, r). Lengths in scene units, the variance in scene units^2.
class GaussianProfile {
 public:
  GaussianProfile() = default;
  GaussianProfile(double variance, double weight) : variance_(variance), weight_(weight) {
    if (!(variance > 0) || !std::isfinite(variance))
      throw std::invalid_argument("Gaussian profile: the variance must be positive and finite (got " +
                                  std::to_string(variance) + ")");
    if (!(weight >= 0) || !std::isfinite(weight))
      throw std::invalid_argument("Gaussian profile: the weight (albedo) must be >= 0 (got " + std::to_string(weight) +
                                  ")");
    r_max_ = std::sqrt(12.46 * variance_);  // King et al. 2013 (corrected; METHODS 1.1)
  }

  double variance() const { return variance_; }
  double weight() const { return weight_; }
  double albedo() const { return weight_; }
  double eval(double r) const { return weight_ * gaussian_2d(variance_, r); }
  double r_max() const { return r_max_; }
  // Energy kept inside r_max: 1 - e^{-6.23}.
  static double kept_fraction() { return -std::expm1(-kGaussianTruncationExponent); }
  // Radius inside which the fraction f of the energy lies: 1 - e^{-r^2/(2v)} = f.
  double r_max(double energy_fraction) const {
    check_fraction(energy_fraction);
    return std::sqrt(-2 * variance_ * std::log1p(-energy_fraction));
  }
  // King et al. 2013 warp, corrected (METHODS 1.1): r = sqrt(-2v ln(1 - xi (1 - e^{-R_m^2/(2v)}))).
  double sample_radius(double xi) const { return std::sqrt(-2 * variance_ * std::log1p(-xi * kept_fraction())); }
  // Radial pdf on [0, R_m]: 2 pi r G / kept = (r / v) e^{-r^2/(2v)} / kept.
  double pdf_radius(double r) const {
    if (r < 0 || r > r_max_) return 0;
    return r / variance_ * std::exp(-r * r / (2 * variance_)) / kept_fraction();
  }

  static void check_fraction(double f) {
    if (!(f > 0 && f < 1))
      throw std::invalid_argument("profile: an energy fraction must lie in (0, 1) (got " + std::to_string(f) + ")");
  }

 private:
  double variance_ = 1;
  double weight_ = 0;
  double r_max_ = std::sqrt(12.46);
};

}  // namespace dermis::sss
