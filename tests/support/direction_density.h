// A density over the sphere of directions and its sampler, checked by Monte Carlo with a
// fixed seed: the density integrates to one (the mean of 4 pi p(w) over uniform directions),
// every draw succeeds and reports p(w), and the sampler draws by the density (the mean of
// 1 / p over its draws is the solid angle where p > 0, measured by the uniform
// directions), each within 4 standard errors.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <random>

#include "dermis/core/vec.h"
#include "dermis/core/warp.h"

namespace dermis::testing {

// density(w) -> float; sample(u1, u2, w&, p&) -> bool.
template <class Density, class Sample>
void expect_density_and_its_sampler(Density&& density, Sample&& sample, uint64_t seed, int n = 400000) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<float> u01(0, 1);
  double sum = 0, sum2 = 0, support = 0, support2 = 0;
  for (int i = 0; i < n; ++i) {
    const Vec3 w = sample_uniform_sphere({u01(rng), u01(rng)});
    const double x = 4 * kPiD * density(w), in = x > 0 ? 4 * kPiD : 0.0;
    sum += x, sum2 += x * x, support += in, support2 += in * in;
  }
  const double mean = sum / n, se = std::sqrt((sum2 / n - mean * mean) / n);
  EXPECT_NEAR(mean, 1.0, 4 * se) << "the density's integral";
  const double solid_angle = support / n, solid_angle_se = std::sqrt((support2 / n - solid_angle * solid_angle) / n);
  double inv = 0, inv2 = 0;
  int drawn = 0;
  for (int i = 0; i < n; ++i) {
    Vec3 w;
    float p = 0;
    if (!sample(u01(rng), u01(rng), w, p)) continue;
    ++drawn;
    EXPECT_NEAR(p, density(w), 1e-3f * p);
    inv += 1 / double(p), inv2 += 1 / (double(p) * p);
  }
  EXPECT_EQ(drawn, n);
  const double mean_inv = inv / n, inv_se = std::sqrt((inv2 / n - mean_inv * mean_inv) / n);
  EXPECT_NEAR(mean_inv, solid_angle, 4 * std::hypot(inv_se, solid_angle_se)) << "the support's solid angle";
}

}  // namespace dermis::testing
