// Checks shared by the profile tests (included by *_test.cpp only): the profile
// integrates to its albedo, the radial pdf integrates to one, and a chi-square test of
// sample_radius against pdf_radius.
#pragma once

#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

#include "dermis/core/rng.h"
#include "dermis/sss/profiles/profile.h"
#include "dermis/sss/profiles/quadrature.h"
#include "support/chi_square.h"

namespace dermis::sss::testing {

// Adaptive Gauss-Kronrod over [a, b] split at b 2^-k (k = 0 .. 60), so that a profile
// concentrated on a small part of the interval is not missed by the first rule.
template <class F>
double integrate_split(const F& f, double a, double b, double tol) {
  double sum = 0, hi = b;
  for (int k = 0; k < 60 && hi > a; ++k) {
    const double lo = std::max(a, 0.5 * hi);
    sum += integrate(f, lo, hi, tol / 60);
    hi = lo;
  }
  if (hi > a) sum += integrate(f, a, hi, tol / 60);
  return sum;
}

// int_0^inf R(r) 2 pi r dr by adaptive Gauss-Kronrod on [0, r_max] and geometric pieces beyond.
inline double plane_integral(const RadialProfile& p) {
  auto f = [&](double r) { return 2 * kPiD * r * p.eval(r); };
  const double tol = 1e-11 * std::max(p.albedo(), 1e-3);
  return integrate_split(f, 0.0, p.r_max(), tol) +
         integrate_to_infinity([&](double s) { return f(p.r_max() + s); }, p.r_max(), tol);
}

// int_0^r_max R(r) 2 pi r dr.
inline double truncated_integral(const RadialProfile& p) {
  return integrate_split([&](double r) { return 2 * kPiD * r * p.eval(r); }, 0.0, p.r_max(), 1e-11);
}

// The albedo is the integral of eval, 1e-3 relative (the brief's tolerance).
inline void expect_integrates_to_albedo(const RadialProfile& p, const std::string& what) {
  const double integral = plane_integral(p);
  EXPECT_NEAR(integral / p.albedo(), 1.0, 1e-3) << what << ": integral " << integral << " albedo " << p.albedo();
}

// The radial pdf integrates to one over [0, r_max] (1e-4) and vanishes beyond; then
// n samples (fixed seed) binned in `bins` bins at energy quantiles are compared with
// the expected counts from integrating pdf_radius over each bin (chi-square,
// significance kChiSquareAlpha).
inline void expect_sampler_matches_pdf(const RadialProfile& p, const std::string& what, uint64_t seed, int n = 200000,
                                       int bins = 64) {
  const double r_max = p.r_max();
  std::vector<double> edges(bins + 1);
  edges[0] = 0;
  for (int i = 1; i < bins; ++i) edges[i] = p.r_max(0.999 * i / bins);
  edges[bins] = r_max;
  for (int i = 1; i <= bins; ++i) ASSERT_GT(edges[i], edges[i - 1]) << what << ": bin edges not increasing at " << i;

  std::vector<double> expected(bins);
  double pdf_total = 0;
  for (int i = 0; i < bins; ++i) {
    expected[i] = integrate_split([&](double r) { return p.pdf_radius(r); }, edges[i], edges[i + 1], 1e-10 / bins);
    pdf_total += expected[i];
  }
  EXPECT_NEAR(pdf_total, 1.0, 1e-4) << what << ": the radial pdf does not integrate to one";
  EXPECT_EQ(p.pdf_radius(r_max * 1.0001 + 1e-12), 0.0) << what << ": pdf beyond r_max";
  for (double& e : expected) e *= n / pdf_total;

  std::vector<double> observed(bins, 0.0);
  Rng rng(seed, 17);
  int outside = 0;
  for (int s = 0; s < n; ++s) {
    const double r = p.sample_radius(rng.uniform_double());
    if (!(r >= 0 && r <= r_max)) {
      ++outside;
      continue;
    }
    const int b = int(std::upper_bound(edges.begin(), edges.end(), r) - edges.begin()) - 1;
    observed[std::min(b, bins - 1)] += 1;
  }
  EXPECT_EQ(outside, 0) << what << ": samples outside [0, r_max]";
  const auto result = dermis::testing::chi_square(observed, expected);
  EXPECT_GT(result.p_value, dermis::testing::kChiSquareAlpha)
      << what << ": chi-square " << result.statistic << " with " << result.dof << " dof";
}

inline void expect_consistent_profile(const RadialProfile& p, const std::string& what, uint64_t seed) {
  expect_integrates_to_albedo(p, what);
  expect_sampler_matches_pdf(p, what, seed);
}

}  // namespace dermis::sss::testing
