#include "dermis/sss/profiles/profile.h"

#include <gtest/gtest.h>

namespace dermis::sss {
namespace {

TEST(ProfileVariant, DispatchesToTheConcreteProfile) {
  const BurleyProfile b(0.4, 1.2);
  const RadialProfile p = b;
  for (double r : {0.01, 0.5, 2.0}) {
    EXPECT_EQ(p.eval(r), b.eval(r));
    EXPECT_EQ(p.pdf_radius(r), b.pdf_radius(r));
  }
  EXPECT_EQ(p.sample_radius(0.3), b.sample_radius(0.3));
  EXPECT_EQ(p.r_max(), b.r_max());
  // r_max(fraction) solves for the radius numerically: an inlined copy may round in
  // the last bits differently (seen in the sanitizer build), so 4 ulp, not bit equality.
  EXPECT_DOUBLE_EQ(p.r_max(0.5), b.r_max(0.5));
  EXPECT_EQ(p.albedo(), b.albedo());
  ASSERT_NE(p.get_if<BurleyProfile>(), nullptr);
  EXPECT_EQ(p.get_if<GaussianProfile>(), nullptr);
  EXPECT_EQ(RadialProfile().albedo(), 0.0);
}

TEST(ProfileVariant, RgbBuildersUseEachChannel) {
  const ProfileRGB skin = make_skin_rgb(0.1, RGB(0.8f, 0.6f, 0.4f));
  EXPECT_NEAR(skin[1].albedo(), 0.6, 1e-7);
  ASSERT_NE(skin[0].get_if<SumOfGaussiansProfile>(), nullptr);
  EXPECT_NEAR(skin.r_max(), 0.1 * std::sqrt(12.46 * 7.41), 1e-12);
  const ProfileRGB d = make_dipole_rgb(RGB(0.2f, 0.5f, 0.8f), RGB(1.0f, 0.5f, 0.25f), 1.3);
  EXPECT_NEAR(d[2].albedo(), 0.8, 1e-6);
  EXPECT_NEAR(d[1].get_if<DipoleProfile>()->mean_free_path(), 0.5, 1e-7);
  EXPECT_THROW(make_burley_rgb(RGB(0.5f), RGB(1.0f, -1.0f, 1.0f)), std::invalid_argument);
}

}  // namespace
}  // namespace dermis::sss
