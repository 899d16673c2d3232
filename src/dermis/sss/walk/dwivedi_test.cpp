#include "dermis/sss/walk/dwivedi.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "dermis/core/gauss_legendre.h"
#include "dermis/core/rng.h"
#include "support/chi_square.h"

namespace dermis::sss {
namespace {

// alpha from 1e-3 to 1 - 1e-9: both ends of the solver.
std::vector<double> test_albedos() {
  std::vector<double> a = {1e-3, 2e-3, 5e-3, 0.01, 0.05, 0.1, 0.2, 0.3, 0.4, 0.49, 0.5, 0.6, 0.7, 0.8, 0.9};
  for (int k = 2; k <= 9; ++k) a.push_back(1 - std::pow(10.0, -k));
  return a;
}

// Relative residual of 1 = alpha nu0 atanh(1/nu0) in long double, in the variable the
// equation is well conditioned in: for nu0 near 1 via ln(nu0 - 1) (nu0 - 1 underflows
// below alpha ~ 0.0028), otherwise atanh(x)/x - 1 = (1 - alpha)/alpha with x = 1/nu0
// by its Taylor series (Abramowitz & Stegun 4.6.33), whose right side is what alpha -> 1 resolves.
long double relative_residual(double alpha, const DwivediEigenvalue& e) {
  if (alpha < 0.5) {
    const long double eps = std::exp((long double)e.log_nu0_minus_one);
    const long double lhs = alpha * (1 + eps) * (std::log(2 + eps) - (long double)e.log_nu0_minus_one) / 2;
    return std::abs(lhs - 1);
  }
  const long double x = e.inv_nu0, c = (1 - (long double)alpha) / alpha;
  long double g = 0;
  if (x < 0.5L) {
    long double p = x * x;
    for (int k = 1; k < 400; ++k, p *= x * x) g += p / (2 * k + 1);
  } else {
    g = std::atanh(x) / x - 1;
  }
  return std::abs(g - c) / c;
}

TEST(Dwivedi, EigenvalueSatisfiesTheEquation) {
  for (double alpha : test_albedos()) {
    const DwivediEigenvalue e = dwivedi_eigenvalue(alpha);
    EXPECT_TRUE(std::isfinite(e.nu0) && e.nu0 >= 1) << alpha;
    EXPECT_TRUE(std::isfinite(e.log_nu0_minus_one)) << alpha;
    EXPECT_LT(relative_residual(alpha, e), 1e-10L) << "alpha=" << alpha;
    // The plain form, where nu0 - 1 holds enough digits (1/nu0 rounds to 1 - O(1e-16)).
    if (e.nu0 > 1 + 1e-4) {
      EXPECT_NEAR(alpha * e.nu0 * std::atanh(1 / e.nu0), 1.0, 1e-10) << alpha;
    }
    EXPECT_NEAR(e.inv_nu0 * e.nu0, 1.0, 1e-15);
    EXPECT_NEAR(e.one_minus_inv_nu0, 1 - e.inv_nu0, 1e-15);
  }
}

TEST(Dwivedi, EigenvalueKnownValuesAndAsymptotes) {
  // Reference values of nu0 to the digits given in issue 6.
  EXPECT_NEAR(dwivedi_nu0(0.5), 1.04438, 5e-6);
  EXPECT_NEAR(dwivedi_nu0(0.9), 1.90320, 5e-6);
  EXPECT_NEAR(dwivedi_nu0(0.99), 5.79673, 5e-6);
  // alpha -> 1: x^2/3 + x^4/5 = 1 - alpha to first order, nu0 ~ 1/sqrt(3 (1 - alpha)).
  const double a = 1 - 1e-9;
  EXPECT_NEAR(dwivedi_nu0(a) * std::sqrt(3 * (1 - a)), 1.0, 1e-6);
  // alpha -> 0: nu0 - 1 ~ 2 exp(-2/alpha), a number far below double range at 1e-3.
  EXPECT_NEAR(dwivedi_eigenvalue(1e-3).log_nu0_minus_one, std::log(2.0) - 2000, 1e-9);
  EXPECT_EQ(dwivedi_eigenvalue(1e-3).nu0, 1.0);
  // No absorption: nu0 = infinity, 1/nu0 = 0.
  EXPECT_TRUE(std::isinf(dwivedi_nu0(1.0)));
  EXPECT_EQ(dwivedi_eigenvalue(1.0).inv_nu0, 0.0);
  EXPECT_THROW(dwivedi_eigenvalue(0.0), std::invalid_argument);
  EXPECT_THROW(dwivedi_eigenvalue(1.5), std::invalid_argument);
  EXPECT_THROW(dwivedi_eigenvalue(std::nan("")), std::invalid_argument);
  EXPECT_THROW(DwivediGuide(0.5, 1.0), std::invalid_argument);
}

// Composite Gauss-Legendre on [-1, 1] with panels refined geometrically toward u = 1,
// where p(u) peaks with width nu0 - 1.
double integrate_cos(const DwivediGuide& guide, double lo, double hi) {
  static const QuadratureRule rule = gauss_legendre(24, 0.0, 1.0);
  std::vector<double> edges = {lo};
  for (int k = 0; k <= 16; ++k) {
    const double e = 1 - std::pow(10.0, -k);
    if (e > lo && e < hi) edges.push_back(e);
  }
  edges.push_back(hi);
  double sum = 0;
  for (size_t i = 0; i + 1 < edges.size(); ++i)
    for (size_t j = 0; j < rule.nodes.size(); ++j) {
      const double h = edges[i + 1] - edges[i];
      sum += h * rule.weights[j] * guide.pdf_cos(edges[i] + h * rule.nodes[j]);
    }
  return sum;
}

TEST(Dwivedi, DirectionPdfIntegratesToOne) {
  for (double g : {0.0, 0.8, -0.5})
    for (double alpha : {0.2, 0.3, 0.5, 0.9, 0.99, 0.999, 1.0}) {
      const DwivediGuide guide(alpha, g);
      EXPECT_NEAR(integrate_cos(guide, -1, 1), 1.0, 1e-9) << "alpha=" << alpha << " g=" << g;
    }
  // g = 0: the seed's (alpha/2) nu0/(nu0 - u), normalised by the eigenvalue equation.
  for (double alpha : {0.3, 0.5, 0.9, 0.99}) {
    const DwivediGuide guide(alpha, 0.0);
    const double nu0 = dwivedi_nu0(alpha);
    for (double u : {-1.0, -0.3, 0.2, 0.9, 1.0})
      EXPECT_NEAR(guide.pdf_cos(u) / (0.5 * alpha * nu0 / (nu0 - u)), 1.0, 1e-12) << alpha << " " << u;
    EXPECT_NEAR(guide.kappa(), 1 / nu0, 1e-15);
  }
  // Similarity relation for g > 0: kappa = (1 - alpha g)/nu0(alpha (1 - g)/(1 - alpha g)).
  EXPECT_NEAR(DwivediGuide(0.99, 0.8).kappa(), (1 - 0.99 * 0.8) / dwivedi_nu0(0.99 * 0.2 / (1 - 0.99 * 0.8)), 1e-14);
  EXPECT_EQ(DwivediGuide(0.0, 0.0).kappa(), 0.0);  // nothing to guide
}

// Bins of the cosine: uniform on [-1, 0.9], then geometric toward 1 (the peak).
std::vector<double> cos_bin_edges() {
  std::vector<double> e;
  for (int i = 0; i <= 38; ++i) e.push_back(-1 + 1.9 * i / 38);
  for (int k = 2; k <= 7; ++k) e.push_back(1 - std::pow(10.0, -k));
  e.push_back(1.0);
  return e;
}

TEST(Dwivedi, DirectionSamplerChiSquare) {
  const std::vector<double> edges = cos_bin_edges();
  for (double g : {0.0, 0.8})
    for (double alpha : {0.3, 0.7, 0.95, 0.999}) {
      const DwivediGuide guide(alpha, g);
      const int n = 100000;
      std::vector<double> observed(edges.size() - 1, 0.0), expected(edges.size() - 1);
      Rng rng(7, uint64_t(alpha * 1000), uint64_t(g * 10));
      for (int i = 0; i < n; ++i) {
        const double u = guide.sample_cos(rng.uniform_double());
        ASSERT_TRUE(u >= -1 && u <= 1);
        const size_t b = std::upper_bound(edges.begin(), edges.end(), u) - edges.begin() - 1;
        observed[std::min(b, observed.size() - 1)] += 1;
      }
      for (size_t b = 0; b < expected.size(); ++b) expected[b] = n * integrate_cos(guide, edges[b], edges[b + 1]);
      const auto r = testing::chi_square(observed, expected);
      EXPECT_GT(r.p_value, testing::kChiSquareAlpha) << "alpha=" << alpha << " g=" << g << " chi2=" << r.statistic;
    }
}

TEST(Dwivedi, SamplerIsTheInverseCdfAtTheEnds) {
  for (double alpha : {1e-3, 0.3, 0.9, 1 - 1e-9, 1.0}) {
    const DwivediGuide guide(alpha, 0.0);
    EXPECT_NEAR(guide.sample_cos(0.0), -1.0, 1e-12) << alpha;
    EXPECT_NEAR(guide.sample_cos(1.0), 1.0, 1e-12) << alpha;
    // Median: the CDF ln((nu+1)/(nu-u))/L at the sampled value is 1/2.
    const double u = guide.sample_cos(0.5);
    EXPECT_TRUE(std::isfinite(u));
    if (alpha > 0.1 && alpha < 1) {
      const double nu = dwivedi_nu0(alpha);
      EXPECT_NEAR(std::log((nu + 1) / (nu - u)) / std::log((nu + 1) / (nu - 1)), 0.5, 1e-9) << alpha;
    }
  }
  EXPECT_NEAR(DwivediGuide(1.0, 0.0).sample_cos(0.25), -0.5, 1e-15);  // alpha = 1: uniform
}

}  // namespace
}  // namespace dermis::sss
