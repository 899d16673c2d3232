#include "dermis/materials/free_flight.h"

#include <gtest/gtest.h>

#include <cmath>

#include "dermis/core/rng.h"

namespace dermis {
namespace {

// E[weight; scattered] = sigma_s / sigma_t (1 - exp(-sigma_t d)) and E[weight; passed]
// = exp(-sigma_t d) per channel, whatever the throughput that chooses the channel:
// checked within 4 standard errors of the sample mean.
TEST(FreeFlight, EveryChannelUnbiasedWhateverTheThroughput) {
  const HomogeneousMedium m = HomogeneousMedium::from_coefficients(RGB(0.1f, 0.5f, 2.0f), RGB(1.0f, 2.0f, 0.5f), 1, 0);
  const float d = 0.7f;
  for (RGB beta : {RGB(1, 1, 1), RGB(0.9f, 0.05f, 0.05f), RGB(0.01f, 0.01f, 1.0f)}) {
    Rng rng(7, 1);
    const int n = 400000;
    double s[2][3] = {}, s2[2][3] = {};
    for (int i = 0; i < n; ++i) {
      FreeFlight f = sample_free_flight(m, beta, d, rng.uniform(), rng.uniform());
      ASSERT_TRUE(f.valid);
      for (int c = 0; c < 3; ++c) {
        const double w = f.weight[c];
        s[f.scattered ? 0 : 1][c] += w;
        s2[f.scattered ? 0 : 1][c] += w * w;
      }
    }
    for (int c = 0; c < 3; ++c) {
      const double st = m.sigma_t[c];
      const double expected[2] = {m.sigma_s[c] / st * (1 - std::exp(-st * d)), std::exp(-st * d)};
      for (int k = 0; k < 2; ++k) {
        const double mean = s[k][c] / n, var = s2[k][c] / n - mean * mean;
        EXPECT_NEAR(mean, expected[k], 4 * std::sqrt(var / n) + 1e-12) << "channel " << c << " event " << k;
      }
    }
  }
}

TEST(FreeFlight, ZeroThroughputCarriesNothing) {
  const HomogeneousMedium m = HomogeneousMedium::from_coefficients(RGB(1), RGB(1), 1, 0);
  EXPECT_FALSE(sample_free_flight(m, RGB(0), 1.0f, 0.5f, 0.5f).valid);
}

}  // namespace
}  // namespace dermis
