#include "dermis/sss/profiles/burley.h"

#include <gtest/gtest.h>

#include "dermis/sss/profiles/profile_test_support.h"

namespace dermis::sss {
namespace {

constexpr BurleyParameterisation kAll[] = {
    BurleyParameterisation::VolumeMeanFreePath, BurleyParameterisation::VolumeMeanFreePathSeedText,
    BurleyParameterisation::DiffuseMeanFreePath, BurleyParameterisation::Searchlight};

TEST(ProfileBurley, IntegratesToAlbedoAndSamplesItsPdf) {
  uint64_t seed = 400;
  for (BurleyParameterisation p : kAll)
    for (double a : {0.1, 0.5, 0.9})
      testing::expect_consistent_profile(BurleyProfile(a, 0.8, p),
                                         "burley A=" + std::to_string(a) + " p=" + std::to_string(int(p)), seed++);
}

TEST(ProfileBurley, CardanoInversionMatchesBisection) {
  const BurleyProfile p(0.6, 1.5);
  for (int i = 0; i <= 2000; ++i) {
    const double xi = i / 2000.0 * 0.999999;
    double lo = 0, hi = 1000 * p.shape_length();
    for (int it = 0; it < 200; ++it) {
      const double mid = 0.5 * (lo + hi);
      (p.cdf(mid) < xi ? lo : hi) = mid;
    }
    const double r = p.invert_cdf(xi);
    EXPECT_NEAR(r, 0.5 * (lo + hi), 1e-6 * std::max(r, p.shape_length() * 1e-3)) << "xi " << xi;
  }
}

TEST(ProfileBurley, CdfIsTheIntegralOfThePdfAndTruncationKeepsItsFraction) {
  const BurleyProfile p(0.3, 2.0, BurleyParameterisation::DiffuseMeanFreePath);
  for (double r : {0.01, 0.5, 3.0})
    EXPECT_NEAR(integrate([&](double x) { return 2 * kPiD * x * p.eval(x); }, 0, r, 1e-13) / p.albedo(), p.cdf(r),
                1e-9);
  EXPECT_NEAR(p.cdf(p.r_max()), BurleyProfile::kDefaultKeptFraction, 1e-12);
  EXPECT_NEAR(testing::truncated_integral(p) / p.albedo(), BurleyProfile::kDefaultKeptFraction, 1e-6);
}

TEST(ProfileBurley, ScaleFits) {
  // Christensen & Burley 2015 / METHODS 1.4 at A = 0.5 and A = 0.9.
  EXPECT_NEAR(burley_scale(0.5, BurleyParameterisation::VolumeMeanFreePath), 1.35 + 7 * 0.027, 1e-15);
  EXPECT_NEAR(burley_scale(0.9, BurleyParameterisation::VolumeMeanFreePath), 0.95 + 0.007, 1e-12);
  EXPECT_NEAR(burley_scale(0.9, BurleyParameterisation::VolumeMeanFreePathSeedText), 0.95 - 0.007, 1e-12);
  EXPECT_NEAR(burley_scale(0.5, BurleyParameterisation::DiffuseMeanFreePath), 1.4 + 3.5 * 0.09, 1e-15);
  EXPECT_NEAR(burley_scale(0.33, BurleyParameterisation::Searchlight), 3.5, 1e-15);
}

TEST(ProfileBurley, RejectsBadParameters) {
  EXPECT_THROW(BurleyProfile(1.2, 1.0), std::invalid_argument);
  EXPECT_THROW(BurleyProfile(0.5, 0.0), std::invalid_argument);
  EXPECT_THROW(BurleyProfile(0.5, 1.0, BurleyParameterisation::Searchlight, 1.0), std::invalid_argument);
}

}  // namespace
}  // namespace dermis::sss
