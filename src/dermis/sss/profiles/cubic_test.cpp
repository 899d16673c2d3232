#include "dermis/sss/profiles/cubic.h"

#include <gtest/gtest.h>

#include "dermis/sss/profiles/profile_test_support.h"

namespace dermis::sss {
namespace {

TEST(ProfileCubic, IntegratesToAlbedoAndSamplesItsPdf) {
  uint64_t seed = 200;
  for (double radius : {0.2, 3.0})
    for (double a : {0.1, 0.5, 0.9})
      testing::expect_consistent_profile(CubicProfile(radius, a), "cubic R=" + std::to_string(radius), seed++);
}

TEST(ProfileCubic, CdfInversionIsExact) {
  for (int i = 0; i <= 1000; ++i) {
    const double xi = i / 1000.0;
    const double x = CubicProfile::invert_cdf(xi);
    EXPECT_NEAR(CubicProfile::cdf(x), xi, 1e-13) << xi;
  }
  // The quintic CDF is the integral of the radial pdf (quadrature).
  const CubicProfile p(2.0, 0.5);
  for (double r : {0.1, 0.5, 1.0, 1.9})
    EXPECT_NEAR(integrate([&](double x) { return p.pdf_radius(x); }, 0, r), CubicProfile::cdf(r / 2.0), 1e-12);
}

TEST(ProfileCubic, RejectsBadParameters) {
  EXPECT_THROW(CubicProfile(0.0, 0.5), std::invalid_argument);
  EXPECT_THROW(CubicProfile(1.0, -1.0), std::invalid_argument);
}

}  // namespace
}  // namespace dermis::sss
