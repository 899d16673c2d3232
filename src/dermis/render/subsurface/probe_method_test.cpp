#include "dermis/render/subsurface/probe_method.h"

#include <gtest/gtest.h>

#include <cmath>

namespace dermis {
namespace {

// Burley profiles of one albedo scale with the mean free path, so their reaches are in
// its ratios: weights albedo x sqrt(mfp / the largest mfp), whatever the scene's unit.
TEST(ProbeChannelWeights, AlbedoTimesTheSquareRootOfTheRelativeReach) {
  for (float unit : {1.0f, 1e-3f, 1e3f}) {
    const sss::ProfileRGB profile = sss::make_burley_rgb(RGB(0.6f), RGB(8, 4, 2) * unit);
    const RGB w = probe_channel_weights(profile);
    EXPECT_NEAR(w[0], profile.channel[0].albedo(), 1e-5) << unit;
    EXPECT_NEAR(w[1], profile.channel[1].albedo() * std::sqrt(0.5), 1e-5) << unit;
    EXPECT_NEAR(w[2], profile.channel[2].albedo() * 0.5, 1e-5) << unit;
  }
}

// A channel that returns nothing keeps a small weight, so that its hits can be found.
TEST(ProbeChannelWeights, NeverZero) {
  const RGB w = probe_channel_weights(sss::make_burley_rgb(RGB(0.8f, 0.0f, 0.4f), RGB(8, 4, 2)));
  EXPECT_GE(w[1], 1e-3f);
  EXPECT_TRUE(std::isfinite(w[0]) && std::isfinite(w[2]));
}

}  // namespace
}  // namespace dermis
