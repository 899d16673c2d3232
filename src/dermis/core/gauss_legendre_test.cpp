#include "dermis/core/gauss_legendre.h"

#include <gtest/gtest.h>

#include <cmath>

namespace dermis {
namespace {

TEST(GaussLegendre, TwoPointRuleIsPlusMinusOneOverSqrt3) {
  QuadratureRule r = gauss_legendre(2);
  EXPECT_NEAR(r.nodes[0], -1 / std::sqrt(3.0), 1e-15);
  EXPECT_NEAR(r.nodes[1], 1 / std::sqrt(3.0), 1e-15);
  EXPECT_NEAR(r.weights[0], 1.0, 1e-15);
}

TEST(GaussLegendre, ExactForPolynomialsUpToDegree2nMinus1) {
  for (int n : {1, 3, 8, 64, 128}) {
    QuadratureRule r = gauss_legendre(n, 0.0, 2.0);
    double wsum = 0;
    for (double w : r.weights) wsum += w;
    EXPECT_NEAR(wsum, 2.0, 1e-13) << n;
    // int_0^2 x^k dx = 2^{k+1} / (k + 1) for k = 2n - 1 (exact) and a few below.
    for (int k : {0, 1, 2 * n - 2, 2 * n - 1}) {
      if (k < 0) continue;
      double sum = 0;
      for (int i = 0; i < n; ++i) sum += r.weights[i] * std::pow(r.nodes[i], k);
      const double exact = std::pow(2.0, k + 1) / (k + 1);
      EXPECT_NEAR(sum / exact, 1.0, 1e-12) << "n=" << n << " k=" << k;
    }
  }
}

TEST(GaussLegendre, RejectsBadArguments) {
  EXPECT_THROW(gauss_legendre(0), std::invalid_argument);
  EXPECT_THROW(gauss_legendre(4, 1.0, 1.0), std::invalid_argument);
}

}  // namespace
}  // namespace dermis
