// Tests of the Henyey-Greenstein phase function and its cosine sampler, in both
// precisions of the one template: the density integrates to one with mean cosine g
// (quadrature), and sampled cosines match it (Pearson chi-square; fixed seeds).
#include "dermis/core/henyey_greenstein.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "dermis/core/gauss_legendre.h"
#include "dermis/core/rng.h"
#include "support/chi_square.h"

namespace dermis {
namespace {

using testing::chi_square;
using testing::kChiSquareAlpha;

constexpr double kTwoPi = 2 * kPiD;

template <class T>
T uniform(Rng& rng) {
  if constexpr (std::is_same_v<T, float>) {
    return rng.uniform();
  } else {
    return rng.uniform_double();
  }
}

template <class T>
class HenyeyGreenstein : public ::testing::Test {};
using Precisions = ::testing::Types<float, double>;
TYPED_TEST_SUITE(HenyeyGreenstein, Precisions);

// int over the sphere = 2 pi int_{-1}^{1} p(cos) dcos = 1 (Gauss-Legendre, 512 nodes:
// its error is far below 1e-9 for g <= 0.9; float evaluation leaves ~1e-7).
TYPED_TEST(HenyeyGreenstein, IntegratesToOne) {
  using T = TypeParam;
  const double tolerance = std::is_same_v<T, float> ? 1e-5 : 1e-9;
  QuadratureRule rule = gauss_legendre(512);
  for (double g : {-0.7, -0.2, 0.0, 0.3, 0.8, 0.9}) {
    double sum = 0;
    for (size_t i = 0; i < rule.nodes.size(); ++i)
      sum += rule.weights[i] * 2 * kPiD * henyey_greenstein<T>(T(rule.nodes[i]), T(g));
    EXPECT_NEAR(sum, 1.0, tolerance) << g;
  }
}

// Midpoint rule over the sphere in theta (2048 steps; the integrand does not depend on
// phi): its error is below 1e-5 even for g = 0.9 (peak width ~ 1 - g; measured 9e-6,
// falling 4x per halving of the step), so 1e-3 only leaves room for float evaluation.
TYPED_TEST(HenyeyGreenstein, IntegratesToOneWithMeanCosineG) {
  using T = TypeParam;
  constexpr int kThetaSteps = 2048;
  for (float g : {-0.7f, 0.0f, 0.3f, 0.9f}) {
    double integral = 0, mean_cos = 0;
    const double dt = kPiD / kThetaSteps;
    for (int i = 0; i < kThetaSteps; ++i) {
      const double theta = (i + 0.5) * dt, c = std::cos(theta);
      const double p = henyey_greenstein<T>(T(c), T(g)) * std::sin(theta) * dt * kTwoPi;
      integral += p;
      mean_cos += c * p;  // the defining property of HG: the mean cosine is g
    }
    EXPECT_NEAR(integral, 1.0, 1e-3) << "g " << g;
    EXPECT_NEAR(mean_cos, g, 1e-3) << "g " << g;
  }
}

// Chi-square of sampled cosines against the pdf integrated over each of 40 bins by
// Gauss-Legendre (16 nodes per bin).
TYPED_TEST(HenyeyGreenstein, SamplerChiSquare) {
  using T = TypeParam;
  const int bins = 40, samples = 200000;
  QuadratureRule rule = gauss_legendre(16);
  for (double g : {-0.6, 0.0, 0.5, 0.9}) {
    Rng rng(11, uint64_t(100 * (g + 1)));
    std::vector<double> observed(bins, 0.0), expected(bins, 0.0);
    for (int i = 0; i < samples; ++i) {
      const double c = sample_henyey_greenstein_cos<T>(uniform<T>(rng), T(g));
      observed[std::min(bins - 1, int((c + 1) / 2 * bins))] += 1;
    }
    for (int b = 0; b < bins; ++b) {
      const double lo = -1 + 2.0 * b / bins, hi = lo + 2.0 / bins;
      double p = 0;
      for (size_t i = 0; i < rule.nodes.size(); ++i)
        p += rule.weights[i] * (hi - lo) / 2 * 2 * kPiD *
             henyey_greenstein<double>(lo + (rule.nodes[i] + 1) / 2 * (hi - lo), g);
      expected[b] = p * samples;
    }
    auto result = chi_square(observed, expected);
    EXPECT_GT(result.p_value, kChiSquareAlpha) << "g=" << g << " chi2=" << result.statistic;
  }
}

// 100 bins in cos(theta), expected counts by the midpoint rule with 256 points per bin
// (the g = 0.9 peak spans ~50 of them), evaluated in the precision under test; and the
// sign convention: the sample mean of the cosine is g, within 4 standard errors.
TYPED_TEST(HenyeyGreenstein, CosineSamplerMatchesPdfAndMeanIsG) {
  using T = TypeParam;
  constexpr int kBins = 100, kSub = 256, kSamples = 200'000;
  uint64_t seed = 20;
  for (float g : {-0.7f, 0.0f, 0.3f, 0.9f}) {
    SCOPED_TRACE(g);
    std::vector<double> observed(kBins, 0.0), expected(kBins, 0.0);
    Rng rng(seed++, 0);
    double sum_cos = 0, sum_cos2 = 0;
    for (int s = 0; s < kSamples; ++s) {
      const T c = sample_henyey_greenstein_cos<T>(uniform<T>(rng), T(g));
      ASSERT_GE(c, T(-1));
      ASSERT_LE(c, T(1));
      observed[std::min(kBins - 1, int((c + 1) / 2 * kBins))] += 1;
      sum_cos += c;
      sum_cos2 += double(c) * c;
    }
    double total = 0;
    for (int b = 0; b < kBins; ++b) {
      const double c0 = -1 + 2.0 * b / kBins, h = 2.0 / kBins / kSub;
      double p = 0;
      for (int k = 0; k < kSub; ++k) p += kTwoPi * henyey_greenstein<T>(T(c0 + (k + 0.5) * h), T(g)) * h;
      expected[b] = p * kSamples;
      total += p;
    }
    ASSERT_NEAR(total, 1.0, 1e-3);
    auto r = chi_square(observed, expected);
    EXPECT_GT(r.p_value, kChiSquareAlpha) << "chi2 = " << r.statistic << " dof " << r.dof;
    const double mean = sum_cos / kSamples, sigma = std::sqrt((sum_cos2 / kSamples - mean * mean) / kSamples);
    EXPECT_NEAR(mean, g, 4 * sigma);
  }
}

// The float signatures the renderer calls agree with the double template to float
// rounding (the sampler's isotropic cut-off differs: 1e-3 in float, 1e-5 in double).
TEST(HenyeyGreensteinPrecision, FloatAgreesWithDouble) {
  // Same float inputs to both; float rounding of denom = 1 + g^2 - 2 g cos loses about
  // eps (1 + |g|)^2 / denom relative (cancellation near the forward peak), eps = 6e-8.
  for (float g : {-0.7f, 0.0f, 0.3f, 0.9f})
    for (float c : {-1.0f, -0.3f, 0.0f, 0.5f, 0.99f, 1.0f}) {
      const double d = henyey_greenstein<double>(c, g), denom = 1 + double(g) * g - 2.0 * g * c;
      const double tol = 1e-6 * d * (1 + std::abs(g)) * (1 + std::abs(g)) / denom;
      EXPECT_NEAR(henyey_greenstein(c, g), d, tol) << g << " " << c;
    }
  for (double g : {-0.7, 0.002, 0.3, 0.9})
    for (double u : {0.0, 0.1, 0.5, 0.9, 0.999})
      EXPECT_NEAR(sample_henyey_greenstein_cos(float(u), float(g)), sample_henyey_greenstein_cos<double>(u, g), 2e-4)
          << g << " " << u;
}

}  // namespace
}  // namespace dermis
