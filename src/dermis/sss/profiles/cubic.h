// The cubic radial profile R(r) = A 10 (R_max - r)^3 / (pi R_max^5) on [0, R_max]
// (used by Arnold and early Cycles; King et al. 2013 mention it; METHODS 1.2).
// Sampled by inverting its exact radial CDF, a quintic, with safeguarded Newton.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

#include "dermis/sss/profiles/gaussian.h"

namespace dermis::sss {

class CubicProfile {
 public:
  CubicProfile() = default;
  // radius R_max in scene units, albedo A in [0, 1].
  CubicProfile(double radius, double albedo) : radius_(radius), albedo_(albedo) {
    if (!(radius > 0) || !std::isfinite(radius))
      throw std::invalid_argument("cubic profile: the radius must be positive and finite (got " +
                                  std::to_string(radius) + ")");
    if (!(albedo >= 0) || !std::isfinite(albedo))
      throw std::invalid_argument("cubic profile: the albedo must be >= 0 (got " + std::to_string(albedo) + ")");
  }

  double radius() const { return radius_; }
  double albedo() const { return albedo_; }
  // METHODS 1.2: R(r) = A 10 (R_max - r)^3 / (pi R_max^5).
  double eval(double r) const {
    if (r >= radius_) return 0;
    const double d = radius_ - r;
    return albedo_ * 10 * d * d * d / (kPiD * radius_ * radius_ * radius_ * radius_ * radius_);
  }
  double r_max() const { return radius_; }
  double r_max(double energy_fraction) const {
    GaussianProfile::check_fraction(energy_fraction);
    return radius_ * invert_cdf(energy_fraction);
  }
  double sample_radius(double xi) const { return radius_ * invert_cdf(xi); }
  // Radial pdf with x = r / R_max: 2 pi r R / A = 20 x (1 - x)^3 / R_max.
  double pdf_radius(double r) const {
    if (r < 0 || r > radius_) return 0;
    const double x = r / radius_, y = 1 - x;
    return 20 * x * y * y * y / radius_;
  }

  // Radial CDF in x = r / R_max: integral of 20 x (1-x)^3 = 10x^2 - 20x^3 + 15x^4 - 4x^5.
  static double cdf(double x) { return x * x * (10 + x * (-20 + x * (15 - 4 * x))); }
  // Solves cdf(x) = xi on [0, 1]: Newton steps kept inside a shrinking bisection bracket.
  static double invert_cdf(double xi) {
    if (!(xi > 0)) return 0;
    if (!(xi < 1)) return 1;
    // Start from a 64-entry inverse table of the (parameter-free) CDF, built once.
    static const std::array<double, 65> table = [] {
      std::array<double, 65> t{};
      for (int i = 0; i <= 64; ++i) {
        double lo = 0, hi = 1;
        for (int it = 0; it < 60; ++it) (cdf(0.5 * (lo + hi)) < i / 64.0 ? lo : hi) = 0.5 * (lo + hi);
        t[i] = 0.5 * (lo + hi);
      }
      return t;
    }();
    const double u = xi * 64;
    const int i = std::min(int(u), 63);
    double lo = table[i], hi = table[i + 1];
    double x = lo + (u - i) * (hi - lo);
    for (int it = 0; it < 100; ++it) {
      const double f = cdf(x) - xi;
      if (f == 0) return x;
      if (f < 0)
        lo = x;
      else
        hi = x;
      const double y = 1 - x;
      const double df = 20 * x * y * y * y;
      double next = df > 0 ? x - f / df : 0.5 * (lo + hi);
      if (!(next >= lo && next <= hi)) next = 0.5 * (lo + hi);
      if (std::abs(next - x) <= 1e-15 || hi - lo <= 1e-15) return next;
      x = next;
    }
    return x;
  }

 private:
  double radius_ = 1;
  double albedo_ = 0;
};

}  // namespace dermis::sss
