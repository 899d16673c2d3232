#include "dermis/sss/profiles/sum_of_gaussians.h"

#include <gtest/gtest.h>

#include "dermis/sss/profiles/profile_test_support.h"

namespace dermis::sss {
namespace {

TEST(ProfileSumOfGaussians, SkinPresetIsTable14_1) {
  // GPU Gems 3 ch. 14, Table 14-1: the weights of each channel sum to one, and the
  // red channel's widest lobe is 7.41 mm^2 with weight 0.078.
  const auto skin = skin_sum_of_gaussians(1.0);
  for (int c = 0; c < 3; ++c) {
    EXPECT_EQ(skin[c].lobe_count(), 6);
    EXPECT_NEAR(skin[c].albedo(), 1.0, 1e-12) << "channel " << c;
  }
  EXPECT_DOUBLE_EQ(skin[0].lobe(5).variance(), 7.41);
  EXPECT_DOUBLE_EQ(skin[0].lobe(5).weight(), 0.078);
  EXPECT_DOUBLE_EQ(skin[2].lobe(0).weight(), 0.649);
  // Scene units: 10 units per mm scales variances by 100.
  const auto scaled = skin_sum_of_gaussians(10.0, RGB(0.5f, 0.4f, 0.3f));
  EXPECT_DOUBLE_EQ(scaled[1].lobe(2).variance(), 18.7);
  EXPECT_NEAR(scaled[2].albedo(), 0.3, 1e-7);
  EXPECT_NEAR(scaled[0].r_max(), std::sqrt(12.46 * 741.0), 1e-9);
}

TEST(ProfileSumOfGaussians, IntegratesToAlbedoAndSamplesTheLobeMixture) {
  uint64_t seed = 100;
  const auto skin = skin_sum_of_gaussians(1.0, RGB(0.9f, 0.5f, 0.1f));
  for (int c = 0; c < 3; ++c) testing::expect_consistent_profile(skin[c], "skin channel " + std::to_string(c), seed++);
  const SumOfGaussiansProfile two({0.01, 4.0}, {0.3, 0.2});
  testing::expect_consistent_profile(two, "two lobes", seed++);
}

TEST(ProfileSumOfGaussians, PdfIsTheWeightedMixtureOfLobes) {
  const SumOfGaussiansProfile p({0.05, 0.5, 2.0}, {0.2, 0.5, 0.3});
  for (double r : {0.01, 0.3, 1.0, 3.0}) {
    double mix = 0;
    for (int i = 0; i < 3; ++i) mix += p.lobe_probability(i) * p.lobe(i).pdf_radius(r);
    EXPECT_DOUBLE_EQ(p.pdf_radius(r), mix);
  }
  EXPECT_NEAR(p.lobe_probability(1), 0.5, 1e-15);
  // r_max(f) keeps exactly f of the (untruncated) energy.
  const double r = p.r_max(0.9);
  EXPECT_NEAR(integrate([&](double x) { return 2 * kPiD * x * p.eval(x); }, 0, r, 1e-12) / p.albedo(), 0.9, 1e-9);
}

TEST(ProfileSumOfGaussians, RejectsBadParameters) {
  EXPECT_THROW(SumOfGaussiansProfile({1.0}, {0.1, 0.2}), std::invalid_argument);
  EXPECT_THROW(SumOfGaussiansProfile({}, {}), std::invalid_argument);
  EXPECT_THROW(skin_sum_of_gaussians(0.0), std::invalid_argument);
}

}  // namespace
}  // namespace dermis::sss
