// Quadrature and histograms over directions on a (theta, phi) grid, for tests of
// direction densities: a pdf integrates to what it should, a sampler matches its pdf.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include "dermis/core/vec.h"
#include "support/chi_square.h"

namespace dermis::testing {

inline Vec3 direction_at(double theta, double phi) {
  return {float(std::sin(theta) * std::cos(phi)), float(std::sin(theta) * std::sin(phi)), float(std::cos(theta))};
}

// Midpoint rule for the integral of f(direction) d omega over theta in [t0, t1],
// phi in [p0, p1] (d omega = sin theta d theta d phi).
template <class F>
double integrate_directions(const F& f, double t0, double t1, int n_theta, double p0, double p1, int n_phi) {
  const double dt = (t1 - t0) / n_theta, dp = (p1 - p0) / n_phi;
  double sum = 0;
  for (int i = 0; i < n_theta; ++i) {
    const double theta = t0 + (i + 0.5) * dt, st = std::sin(theta);
    for (int j = 0; j < n_phi; ++j) sum += f(direction_at(theta, p0 + (j + 0.5) * dp)) * st;
  }
  return sum * dt * dp;
}

// An integral over theta in [0, theta_max] and all phi on an n_theta x n_phi grid and on
// one twice as coarse: the midpoint rule's error is O(h^2), so that of the fine grid is
// about |fine - coarse| / 3; `error` reports |fine - coarse| (a safe bound).
struct GridIntegral {
  double value = 0, error = 0;
};
template <class F>
GridIntegral integrate_with_error(const F& f, double theta_max, int n_theta, int n_phi) {
  const double fine = integrate_directions(f, 0, theta_max, n_theta, 0, 2 * kPiD, n_phi);
  const double coarse = integrate_directions(f, 0, theta_max, n_theta / 2, 0, 2 * kPiD, n_phi / 2);
  return {fine, std::abs(fine - coarse)};
}

// Pearson chi-square of sampled directions against a density over theta in
// [0, theta_max] x phi in [0, 2 pi), binned n_theta x n_phi, expected counts from the
// density integrated over each cell (midpoint rule, sub x sub points). One more cell
// holds the samples that the sampler did not return (`lost`), with the expected count
// samples (1 - integral of the pdf): a sampler whose pdf integrates to one minus its
// failure probability passes.
class DirectionHistogram {
 public:
  DirectionHistogram(double theta_max, int n_theta, int n_phi)
      : theta_max_(theta_max), nt_(n_theta), np_(n_phi), counts_(std::size_t(n_theta) * n_phi + 1, 0.0) {}

  void add(Vec3 w) {
    const double theta = std::acos(std::clamp(double(w.z), -1.0, 1.0));
    double phi = std::atan2(double(w.y), double(w.x));
    if (phi < 0) phi += 2 * kPiD;
    const int i = std::min(nt_ - 1, int(theta / theta_max_ * nt_)), j = std::min(np_ - 1, int(phi / (2 * kPiD) * np_));
    counts_[std::size_t(i) * np_ + j] += 1;
    ++samples_;
  }
  void add_lost() {
    counts_.back() += 1;
    ++samples_;
  }

  template <class Pdf>
  ChiSquareResult test(const Pdf& pdf, int sub = 8) const {
    std::vector<double> expected(counts_.size(), 0.0);
    const double dt = theta_max_ / nt_, dp = 2 * kPiD / np_;
    double total = 0;
    for (int i = 0; i < nt_; ++i)
      for (int j = 0; j < np_; ++j) {
        const double p = integrate_directions(pdf, i * dt, (i + 1) * dt, sub, j * dp, (j + 1) * dp, sub);
        expected[std::size_t(i) * np_ + j] = p * samples_;
        total += p;
      }
    expected.back() = std::max(0.0, 1 - total) * samples_;
    return chi_square(counts_, expected);
  }

  double lost_fraction() const { return counts_.back() / samples_; }
  double samples() const { return samples_; }

 private:
  double theta_max_;
  int nt_, np_;
  std::vector<double> counts_;
  double samples_ = 0;
};

}  // namespace dermis::testing
