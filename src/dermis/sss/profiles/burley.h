// The Christensen-Burley empirical profile (Christensen & Burley 2015; METHODS 1.4):
// R(r) = A s (e^{-s r/l} + e^{-s r/(3l)}) / (8 pi l r), written with d = l / s as
// R(r) = A (e^{-r/d} + e^{-r/(3d)}) / (8 pi d r). Sampled in closed form (Cardano) from
// the radial CDF, truncated at the radius that keeps `kept_fraction` of the energy;
// the pdf is renormalised by that fraction.
#pragma once

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "dermis/sss/profiles/gaussian.h"

namespace dermis::sss {

// Which length the user's l is, i.e. which fit of the scale s(A) applies.
enum class BurleyParameterisation {
  // l = volume mean free path: s = 1.85 - A + 7 |A - 0.8|^3 (Christensen & Burley 2015, eq. 2 as
  // corrected in METHODS 1.4).
  VolumeMeanFreePath,
  // Same, with the seed's extracted text s = 1.85 - A + 7 (0.8 - A)^3 (differs for A > 0.8 only).
  VolumeMeanFreePathSeedText,
  // l = diffuse mean free path on the surface: s = 1.9 - A + 3.5 (A - 0.8)^2.
  DiffuseMeanFreePath,
  // searchlight configuration: s = 3.5 + 100 (A - 0.33)^4.
  Searchlight,
};

// The scale s(A) of each parameterisation (Christensen & Burley 2015; METHODS 1.4).
inline double burley_scale(double albedo, BurleyParameterisation p) {
  const double a = albedo;
  switch (p) {
    case BurleyParameterisation::VolumeMeanFreePath: {
      const double t = std::abs(a - 0.8);
      return 1.85 - a + 7 * t * t * t;
    }
    case BurleyParameterisation::VolumeMeanFreePathSeedText: {
      const double t = 0.8 - a;
      return 1.85 - a + 7 * t * t * t;
    }
    case BurleyParameterisation::DiffuseMeanFreePath:
      return 1.9 - a + 3.5 * (a - 0.8) * (a - 0.8);
    case BurleyParameterisation::Searchlight: {
      const double t = (a - 0.33) * (a - 0.33);
      return 3.5 + 100 * t * t;
    }
  }
  return 1;
}

class BurleyProfile {
 public:
  static constexpr double kDefaultKeptFraction = 0.999;

  BurleyProfile() = default;
  // albedo A in [0, 1]; mean_free_path l in scene units (its meaning set by p).
  BurleyProfile(double albedo, double mean_free_path,
                BurleyParameterisation p = BurleyParameterisation::VolumeMeanFreePath,
                double kept_fraction = kDefaultKeptFraction)
      : albedo_(albedo), kept_(kept_fraction) {
    if (!(albedo >= 0 && albedo <= 1))
      throw std::invalid_argument("Christensen-Burley profile: the albedo must lie in [0, 1] (got " +
                                  std::to_string(albedo) + ")");
    if (!(mean_free_path > 0) || !std::isfinite(mean_free_path))
      throw std::invalid_argument("Christensen-Burley profile: the mean free path must be positive (got " +
                                  std::to_string(mean_free_path) + ")");
    GaussianProfile::check_fraction(kept_fraction);
    scale_ = burley_scale(albedo, p);
    d_ = mean_free_path / scale_;
    inverse_3d_ = 1 / (3 * d_);
    pdf_factor_ = 1 / (4 * d_ * kept_);
    r_max_ = r_max(kept_fraction);
  }

  double albedo() const { return albedo_; }
  double scale() const { return scale_; }     // s
  double shape_length() const { return d_; }  // d = l / s
  double kept_fraction() const { return kept_; }
  // Christensen & Burley 2015, eq. 1. Below 1e-6 d the (integrable) 1/r singularity
  // is clamped so that the value stays finite.
  double eval(double r) const {
    r = std::max(r, 1e-6 * d_);
    const double u = third_exponential(r);
    return albedo_ * (u * u * u + u) / (8 * kPiD * d_ * r);
  }
  double r_max() const { return r_max_; }
  double r_max(double energy_fraction) const {
    GaussianProfile::check_fraction(energy_fraction);
    return invert_cdf(energy_fraction);
  }
  double sample_radius(double xi) const { return invert_cdf(xi * kept_); }
  // 2 pi r R / (A kept) = (e^{-r/d} + e^{-r/(3d)}) / (4 d kept) on [0, r_max].
  double pdf_radius(double r) const {
    if (r < 0 || r > r_max_) return 0;
    const double u = third_exponential(r);
    return (u * u * u + u) * pdf_factor_;
  }
  // Radial CDF F(r) = 1 - e^{-r/d}/4 - 3 e^{-r/(3d)}/4 (Christensen & Burley 2015, sec. 3).
  double cdf(double r) const {
    const double u = third_exponential(r);
    return 1 - 0.25 * u * u * u - 0.75 * u;
  }

  // F(r) = xi in closed form: with u = e^{-r/(3d)}, u^3 + 3u - 4(1 - xi) = 0 (METHODS 1.4).
  // Cardano: with c = 2(1 - xi) and a = cbrt(c + sqrt(c^2 + 1)) the real root is
  // u = a - 1/a = 2c / (a^2 + 1 + 1/a^2) (the second form avoids cancellation).
  double invert_cdf(double xi) const {
    const double c = 2 * (1 - xi);
    const double a = std::cbrt(c + std::sqrt(c * c + 1));
    const double u = 2 * c / (a * a + 1 + 1 / (a * a));
    return std::max(0.0, -3 * d_ * std::log(u));
  }

 private:
  // u = e^{-r/(3d)}; the profile's other exponential is e^{-r/d} = u^3: one exp, not two
  // (the probes evaluate R and every strategy's pdf at each hit).
  double third_exponential(double r) const { return std::exp(-r * inverse_3d_); }

  double albedo_ = 0;
  double kept_ = kDefaultKeptFraction;
  double scale_ = 1;
  double d_ = 1;
  double inverse_3d_ = 1.0 / 3;  // 1 / (3d): the probes evaluate the pdf at every hit, a division each
  double pdf_factor_ = 1 / (4 * kDefaultKeptFraction);  // 1 / (4 d kept)
  double r_max_ = 1;
};

}  // namespace dermis::sss
