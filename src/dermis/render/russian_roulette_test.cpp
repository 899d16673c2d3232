#include "dermis/render/russian_roulette.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "dermis/core/rng.h"

namespace dermis {
namespace {

TEST(RussianRoulette, SurvivalFollowsTheThroughputBelowTheThreshold) {
  // pbrt-v4's rule at surfaces: survival probability rr below 1.
  EXPECT_EQ(roulette_survival(1.0f, kSurfaceRouletteThreshold), 1.0f);
  EXPECT_EQ(roulette_survival(3.0f, kSurfaceRouletteThreshold), 1.0f);
  EXPECT_FLOAT_EQ(roulette_survival(0.3f, kSurfaceRouletteThreshold), 0.3f);
  // In a medium: none above 1/2, 2 rr below.
  EXPECT_EQ(roulette_survival(0.9f, kMediumRouletteThreshold), 1.0f);
  EXPECT_EQ(roulette_survival(0.5f, kMediumRouletteThreshold), 1.0f);
  EXPECT_FLOAT_EQ(roulette_survival(0.3f, kMediumRouletteThreshold), 0.6f);
  EXPECT_FLOAT_EQ(roulette_survival(0.01f, kMediumRouletteThreshold), 0.02f);
  // Nothing carried, or a NaN: the path ends.
  EXPECT_EQ(roulette_survival(0.0f, kMediumRouletteThreshold), 0.0f);
  EXPECT_EQ(roulette_survival(-1.0f, kSurfaceRouletteThreshold), 0.0f);
  EXPECT_EQ(roulette_survival(std::numeric_limits<float>::quiet_NaN(), kSurfaceRouletteThreshold), 0.0f);
}

TEST(RussianRoulette, SurvivorsReweightedKeepTheMean) {
  // The weight a path carries on, 1/p if it survives (u < p) and 0 otherwise, has mean 1:
  // checked within 4 standard errors for several throughputs at both thresholds.
  Rng rng(7, 0);
  constexpr int kDraws = 200000;
  for (float threshold : {kSurfaceRouletteThreshold, kMediumRouletteThreshold}) {
    for (float rr : {0.05f, 0.3f, 0.45f, 0.8f}) {
      const double p = roulette_survival(rr, threshold);
      double sum = 0, sum2 = 0;
      for (int i = 0; i < kDraws; ++i) {
        const double w = rng.uniform_double() < p ? 1 / p : 0.0;
        sum += w;
        sum2 += w * w;
      }
      const double mean = sum / kDraws;
      const double se = std::sqrt((sum2 / kDraws - mean * mean) / kDraws);
      if (p < 1) {
        EXPECT_GT(se, 0);
        EXPECT_NEAR(mean, 1.0, 4 * se) << "rr " << rr << " threshold " << threshold;
      } else {
        EXPECT_EQ(mean, 1.0);
      }
    }
  }
}

}  // namespace
}  // namespace dermis
