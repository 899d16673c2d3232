#include "dermis/sss/halfspace/hg_phase.h"

#include <gtest/gtest.h>

#include <vector>

#include "dermis/core/rng.h"
#include "dermis/sss/halfspace/gauss_legendre.h"
#include "support/chi_square.h"

namespace dermis::sss {
namespace {

// int over the sphere = 2 pi int_{-1}^{1} p(cos) dcos = 1.
TEST(HalfspaceHG, IntegratesToOne) {
  QuadratureRule rule = gauss_legendre(512);
  for (double g : {-0.7, -0.2, 0.0, 0.3, 0.8, 0.9}) {
    double sum = 0;
    for (size_t i = 0; i < rule.nodes.size(); ++i) sum += rule.weights[i] * 2 * kPiD * hg_phase(rule.nodes[i], g);
    EXPECT_NEAR(sum, 1.0, 1e-9) << g;
  }
}

// Chi-square of sampled cosines against the pdf integrated over each bin by quadrature.
TEST(HalfspaceHG, SamplerChiSquare) {
  const int bins = 40, samples = 200000;
  QuadratureRule rule = gauss_legendre(16);
  for (double g : {-0.6, 0.0, 0.5, 0.9}) {
    Rng rng(11, uint64_t(100 * (g + 1)));
    std::vector<double> observed(bins, 0.0), expected(bins, 0.0);
    for (int i = 0; i < samples; ++i) {
      const double c = sample_hg_cos(rng.uniform_double(), g);
      observed[std::min(bins - 1, int((c + 1) / 2 * bins))] += 1;
    }
    for (int b = 0; b < bins; ++b) {
      const double lo = -1 + 2.0 * b / bins, hi = lo + 2.0 / bins;
      double p = 0;
      for (size_t i = 0; i < rule.nodes.size(); ++i)
        p += rule.weights[i] * (hi - lo) / 2 * 2 * kPiD * hg_phase(lo + (rule.nodes[i] + 1) / 2 * (hi - lo), g);
      expected[b] = p * samples;
    }
    auto result = testing::chi_square(observed, expected);
    EXPECT_GT(result.p_value, testing::kChiSquareAlpha) << "g=" << g << " chi2=" << result.statistic;
  }
}

TEST(HalfspaceHG, DirectionAboutAxisHasRequestedCosine) {
  const Vec3d axis = normalize(Vec3d{0.3, -0.5, 0.8});
  for (double c : {-0.9, 0.0, 0.4, 1.0}) {
    const Vec3d d = direction_about(axis, c, 1.234);
    EXPECT_NEAR(length(d), 1.0, 1e-14);
    EXPECT_NEAR(dot(d, axis), c, 1e-14);
  }
}

}  // namespace
}  // namespace dermis::sss
