#include "dermis/materials/noise.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace dermis {
namespace {

// Perlin 2002: the noise is the gradient ramp of the lattice point there, so it is 0 at
// every integer point (negative ones and ones beyond the period of 256 included).
TEST(PerlinNoise, ZeroAtEveryLatticePoint) {
  for (int x = -300; x <= 300; x += 7)
    for (int y = -260; y <= 260; y += 13)
      for (int z : {-257, -1, 0, 1, 2, 255, 256, 1000})
        ASSERT_EQ(perlin_noise(Vec3(float(x), float(y), float(z))), 0.0f) << x << " " << y << " " << z;
}

// At a lattice point the noise's gradient is that point's gradient vector: one of
// Perlin 2002's 12 edge vectors (two components +-1, one 0).
TEST(PerlinNoise, GradientAtALatticePointIsAnEdgeVector) {
  const float h = 1e-3f;
  for (int k = 0; k < 50; ++k) {
    const Vec3 p(float(k * 3 - 70), float(k % 11), float(k * 5 % 17 - 8));
    float g[3];
    for (int a = 0; a < 3; ++a) {
      Vec3 d(0, 0, 0);
      d[a] = h;
      g[a] = (perlin_noise(p + d) - perlin_noise(p - d)) / (2 * h);
    }
    int nonzero = 0;
    for (float c : g) {
      // fade'(t) = 30 t^2 (1 - t)^2 is O(h^2) at the lattice point: the ramp's slope dominates.
      EXPECT_TRUE(std::abs(c) < 1e-2f || std::abs(std::abs(c) - 1) < 1e-2f) << c;
      nonzero += std::abs(c) > 0.5f;
    }
    EXPECT_EQ(nonzero, 2) << p.x << " " << p.y << " " << p.z;
  }
}

// Bounds: every corner ramp is g . d with g an edge vector and |d_i| <= 1, so |ramp| <= 2,
// and the fade-weighted interpolation is a convex combination: |noise| <= 2. The range is
// also used (not a degenerate, nearly constant function).
TEST(PerlinNoise, StaysWithinItsBoundAndUsesItsRange) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-600, 600);
  float lo = 0, hi = 0;
  for (int i = 0; i < 200000; ++i) {
    const float n = perlin_noise(Vec3(u(rng), u(rng), u(rng)));
    ASSERT_LE(std::abs(n), 2.0f);
    lo = std::min(lo, n);
    hi = std::max(hi, n);
  }
  EXPECT_LT(lo, -0.6f);
  EXPECT_GT(hi, 0.6f);
}

// Continuity (Lipschitz): each partial derivative is at most max fade' (15/8) times the
// largest difference of two ramps (4) plus a ramp's own slope (2): 9.5; along a unit
// direction at most sqrt(3) 9.5 < 17. Steps that cross cell faces included.
TEST(PerlinNoise, IsContinuousAcrossCellFaces) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(-40, 40), s(-1, 1);
  const float h = 1e-3f;
  for (int i = 0; i < 100000; ++i) {
    Vec3 p(u(rng), u(rng), u(rng));
    if (i % 2) p.x = std::round(p.x) - h / 2;  // straddle a face of the lattice
    Vec3 d(s(rng), s(rng), s(rng));
    if (length(d) < 1e-3f) continue;
    d = normalize(d);
    ASSERT_LE(std::abs(perlin_noise(p + d * h) - perlin_noise(p)), 17 * h * 1.01f) << i;
  }
}

TEST(PerlinNoise, IsPeriodicWith256) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(0, 8);
  for (int i = 0; i < 1000; ++i) {
    const Vec3 p(u(rng), u(rng), u(rng));
    EXPECT_NEAR(perlin_noise(p), perlin_noise(p + Vec3(256, -512, 256)), 2e-3f);
  }
}

// The gradient ramps are odd about their lattice point and the fade weights even, so the
// noise integrates to 0 over a period; fBm's octaves (frequencies 1.99^i) nearly so. The
// sample mean of fBm over uniform points of the period cube must be within 4 standard
// errors (from the sample variance) of 0.
TEST(PerlinNoise, FbmMeanOverALargeVolumeIsZeroWithinFourStandardErrors) {
  std::mt19937 rng(2026);
  std::uniform_real_distribution<double> u(0, 256);
  const int n = 200000;
  double sum = 0, sum2 = 0;
  for (int i = 0; i < n; ++i) {
    const double v = fbm(Vec3(float(u(rng)), float(u(rng)), float(u(rng))), 0.5f, 8);
    sum += v;
    sum2 += v * v;
  }
  const double mean = sum / n, var = sum2 / n - mean * mean;
  const double stderr_mean = std::sqrt(var / n);
  EXPECT_GT(var, 0.01);  // not a constant
  EXPECT_LT(std::abs(mean), 4 * stderr_mean) << "mean " << mean << " stderr " << stderr_mean;
}

// The sums as defined (Ebert et al. §2.6; pbrt-v4 with no filter footprint).
TEST(PerlinNoise, FbmAndTurbulenceAreTheirOctaveSums) {
  const Vec3 p(0.3f, 1.7f, -2.2f);
  EXPECT_EQ(fbm(p, 0.5f, 0), 0.0f);
  EXPECT_FLOAT_EQ(fbm(p, 0.5f, 1), perlin_noise(p));
  EXPECT_FLOAT_EQ(fbm(p, 0.7f, 2), perlin_noise(p) + 0.7f * perlin_noise(p * 1.99f));
  EXPECT_FLOAT_EQ(turbulence(p, 0.5f, 0), 0.2f);
  EXPECT_FLOAT_EQ(turbulence(p, 0.7f, 2),
                  std::abs(perlin_noise(p)) + 0.7f * std::abs(perlin_noise(p * 1.99f)) + 0.2f * 0.49f);
  // At a lattice point the first octave is 0: one octave of turbulence is just the tail term.
  EXPECT_FLOAT_EQ(turbulence(Vec3(3, -4, 5), 0.5f, 1), 0.1f);
}

}  // namespace
}  // namespace dermis
