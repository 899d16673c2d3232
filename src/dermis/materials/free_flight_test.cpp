#include "dermis/materials/free_flight.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

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

// E[weight f(t)] = int_0^d sigma_s T(t) f(t) dt per channel, for a finite and an infinite
// segment, with f(t) = 1 + t (closed forms below): within 4 standard errors.
TEST(SegmentPoint, EveryChannelUnbiasedOnFiniteAndInfiniteSegments) {
  const HomogeneousMedium m = HomogeneousMedium::from_coefficients(RGB(0.1f, 0.5f, 2.0f), RGB(1.0f, 2.0f, 0.5f), 1, 0);
  for (float d : {0.05f, 0.7f, std::numeric_limits<float>::infinity()}) {
    for (RGB beta : {RGB(1, 1, 1), RGB(0.9f, 0.05f, 0.05f), RGB(0.01f, 0.01f, 1.0f)}) {
      Rng rng(11, 3);
      const int n = 400000;
      double s[3] = {}, s2[3] = {};
      for (int i = 0; i < n; ++i) {
        SegmentPoint p = sample_segment_point(m, beta, d, rng.uniform(), rng.uniform());
        ASSERT_TRUE(p.valid);
        ASSERT_LT(p.t, d);
        for (int c = 0; c < 3; ++c) {
          const double w = p.weight[c] * (1.0 + p.t);
          s[c] += w;
          s2[c] += w * w;
        }
      }
      for (int c = 0; c < 3; ++c) {
        const double st = m.sigma_t[c], ss = m.sigma_s[c];
        // int_0^d ss e^{-st t} (1 + t) dt = ss [(1 - e)/st + (1 - e (1 + st d))/st^2], e = e^{-st d}.
        const double e = std::isinf(d) ? 0.0 : std::exp(-st * d), sd = std::isinf(d) ? 0.0 : st * d;
        const double expected = ss * ((1 - e) / st + (1 - e * (1 + sd)) / (st * st));
        const double mean = s[c] / n, var = s2[c] / n - mean * mean;
        EXPECT_NEAR(mean, expected, 4 * std::sqrt(var / n) + 1e-12) << "channel " << c << " d " << d;
      }
    }
  }
}

// The free flight's channel preference is (sigma_a / sigma_t)^-1/2: channels of little
// absorption are chosen more often (a channel without absorption as one of 1e-6).
TEST(FreeFlight, ChannelPreferenceFollowsAbsorption) {
  const HomogeneousMedium m =
      HomogeneousMedium::from_coefficients(RGB(0.01f, 0.5f, 0.0f), RGB(0.99f, 0.5f, 2.0f), 2, 0);
  EXPECT_NEAR(m.channel_preference[0], 10.0f, 1e-4f);
  EXPECT_NEAR(m.channel_preference[1], std::sqrt(2.0f), 1e-5f);
  EXPECT_NEAR(m.channel_preference[2], 1000.0f, 1e-2f);
  const HomogeneousMedium empty = HomogeneousMedium::from_coefficients(RGB(0.0f), RGB(0.0f), 1, 0);
  EXPECT_EQ(empty.channel_preference, RGB(1));
}

TEST(SegmentPoint, ChannelsThatDoNotScatterAreNeverChosen) {
  // Only the green channel scatters: red and blue have sigma_s = 0 (red absorbs, blue is empty).
  const HomogeneousMedium m = HomogeneousMedium::from_coefficients(RGB(1.0f, 0.2f, 0.0f), RGB(0.0f, 1.0f, 0.0f), 1, 0);
  Rng rng(5, 1);
  for (int i = 0; i < 1000; ++i) {
    SegmentPoint p = sample_segment_point(m, RGB(1, 1, 1), 2.0f, rng.uniform(), rng.uniform());
    ASSERT_TRUE(p.valid);
    EXPECT_EQ(p.weight[0], 0.0f);
    EXPECT_EQ(p.weight[2], 0.0f);
    EXPECT_TRUE(std::isfinite(p.weight[1]));
  }
  EXPECT_FALSE(sample_segment_point(m, RGB(1, 0, 1), 2.0f, 0.5f, 0.5f).valid);
}

TEST(FreeFlight, ZeroThroughputCarriesNothing) {
  const HomogeneousMedium m = HomogeneousMedium::from_coefficients(RGB(1), RGB(1), 1, 0);
  EXPECT_FALSE(sample_free_flight(m, RGB(0), 1.0f, 0.5f, 0.5f).valid);
}

// The exponential's quantile -ln(1 - u) against log1p in double: within 2 float ulps
// over [0, 1), down to the smallest fractions a 32-bit sample gives (2^-32) and for the
// largest float below 1.
TEST(FreeFlight, ExponentialQuantileIsAccurateOverTheUnitInterval) {
  std::vector<float> us = {0.0f, 0x1p-32f, 0x1p-24f, 1e-6f, 0x1p-12f, 0.01f, 0.3f, 0.5f, 0.9f, 0.999f, 0x1.fffffep-1f};
  for (float u = 1e-7f; u < 1; u = u * 1.37f + 1e-7f) us.push_back(u);
  for (float u : us) {
    const double expected = -std::log1p(-double(u));
    const float got = exponential_quantile(u);
    const double ulp = std::nextafter(float(expected), 2.0f * float(expected) + 1) - float(expected);
    EXPECT_NEAR(got, expected, 2 * ulp + 1e-45) << "u " << u;
  }
}

// The segment's 1 - T per channel against expm1 in double: within 1e-6 relative for
// optical depths from 1e-6 to 50 (1 - e^-x alone loses digits as x -> 0), 1 on an
// infinite segment, 0 in a channel that does not attenuate; T(t_max) as transmittance().
TEST(FreeFlight, SegmentCapturedFractionIsAccurateAtEveryOpticalDepth) {
  const HomogeneousMedium m = HomogeneousMedium::from_coefficients(RGB(0.5f, 0.0f, 2.0f), RGB(0.5f, 0.0f, 8.0f), 1, 0);
  for (float t : {1e-6f, 1e-4f, 0.01f, 0.0624f, 0.0626f, 0.3f, 1.0f, 5.0f, 50.0f}) {
    const MediumSegment s = medium_segment(m, t);
    for (int c = 0; c < 3; ++c) {
      const double expected = -std::expm1(-double(m.sigma_t[c]) * double(t));
      EXPECT_NEAR(s.captured[c], expected, 1e-6 * expected) << "t " << t << " channel " << c;
      EXPECT_EQ(s.transmittance[c], m.transmittance(t)[c]);
    }
  }
  const MediumSegment infinite = medium_segment(m, std::numeric_limits<float>::infinity());
  EXPECT_EQ(infinite.captured, RGB(1.0f, 1.0f, 1.0f));
  EXPECT_EQ(infinite.transmittance, RGB(0.0f, 1.0f, 0.0f));
}

}  // namespace
}  // namespace dermis
