#include "dermis/sss/pointcloud/illumination_detail.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <random>
#include <stdexcept>
#include <vector>

namespace dermis::sss::pointcloud {
namespace {

// Blue-noise points on the unit square z = 0, with E(x, y) at each.
struct Cloud {
  std::vector<SurfacePoint> points;
  std::vector<float> irradiance, variance;
};
Cloud square_cloud(std::size_t n, const std::function<double(double, double)>& E, uint64_t seed = 7) {
  const std::vector<Vec3> p = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  const std::vector<uint32_t> idx = {0, 1, 2, 0, 2, 3};
  Cloud c;
  c.points = distribute_points(p, idx, n, seed);
  for (const SurfacePoint& s : c.points) c.irradiance.push_back(float(E(s.position.x, s.position.y)));
  c.variance.assign(n, 0.0f);
  return c;
}

TEST(IlluminationDetail, ConstantIrradianceHasNoDetail) {
  const Cloud c = square_cloud(2000, [](double, double) { return 3.0; });
  const IlluminationDetail d = illumination_detail(c.points, c.irradiance, c.variance);
  EXPECT_NEAR(d.mean_irradiance, 3.0, 1e-6);
  EXPECT_NEAR(d.relative_squared_error, 0.0, 1e-12);
  EXPECT_LT(d.relative_error(), 1e-6);
}

// Constant E measured with Monte Carlo noise of known variance: the noise is removed, so
// the detail is zero within 4 standard errors of the estimator; not removing it (variance
// given as 0) reads the noise as detail: about sigma^2 (1 + sum w^2) / E^2.
TEST(IlluminationDetail, TheEstimatesOwnNoiseIsNotDetail) {
  Cloud c = square_cloud(4000, [](double, double) { return 1.0; });
  std::mt19937_64 rng(11);
  std::normal_distribution<float> noise(0.0f, 0.1f);
  for (float& e : c.irradiance) e += noise(rng);
  c.variance.assign(c.points.size(), 0.01f);
  const IlluminationDetail d = illumination_detail(c.points, c.irradiance, c.variance);
  std::printf("noise only: relative squared error %.3g +- %.3g (noise %.3g)\n", d.relative_squared_error,
              d.standard_error, d.noise);
  EXPECT_LT(std::abs(d.relative_squared_error), 4 * d.standard_error);
  const std::vector<float> none(c.points.size(), 0.0f);
  const IlluminationDetail raw = illumination_detail(c.points, c.irradiance, none);
  EXPECT_GT(raw.relative_squared_error, 0.01 - 4 * raw.standard_error);  // at least sigma^2
  EXPECT_GT(raw.relative_squared_error, 10 * raw.standard_error);
}

// The rule next_point_count grows the cloud by assumes a relative error falling like the
// spacing h ~ N^-1/2. A smooth gradient falls at least that fast (the asymmetry of the
// neighbours, O(h), partly cancels in blue noise: exponent <= -0.4); a shadow edge slower,
// like the band of mispredicted points one spacing wide (squared error ~ h: exponent
// -1/4 +- 0.1), which later rounds make up. Measured between N and 16 N.
TEST(IlluminationDetail, TheMissFallsWithTheSpacingAsTheRefinementRuleAssumes) {
  auto exponent = [](const std::function<double(double, double)>& E) {
    const Cloud a = square_cloud(1000, E), b = square_cloud(16000, E);
    const double ea = illumination_detail(a.points, a.irradiance, a.variance).relative_error();
    const double eb = illumination_detail(b.points, b.irradiance, b.variance).relative_error();
    std::printf("relative error %.4g at 1000 points, %.4g at 16000: exponent %.3f\n", ea, eb,
                std::log(eb / ea) / std::log(16.0));
    return std::log(eb / ea) / std::log(16.0);
  };
  EXPECT_LT(exponent([](double x, double y) { return 1 + x + 0.5 * y; }), -0.4);
  EXPECT_NEAR(exponent([](double x, double) { return x < 0.37 ? 1.0 : 0.1; }), -0.25, 0.1);
}

TEST(IlluminationDetail, AnUnlitObjectNeedsNoPoints) {
  const Cloud c = square_cloud(500, [](double, double) { return 0.0; });
  const IlluminationDetail d = illumination_detail(c.points, c.irradiance, c.variance);
  EXPECT_EQ(d.relative_error(), 0.0);
  EXPECT_EQ(next_point_count(500, d.relative_error(), 0.02, 100000), 500u);
}

TEST(IlluminationDetail, RefusesMismatchedOrTooFewValues) {
  const Cloud c = square_cloud(20, [](double, double) { return 1.0; });
  const std::vector<float> short_list(19, 1.0f);
  EXPECT_THROW(illumination_detail(c.points, short_list, c.variance), std::invalid_argument);
  EXPECT_THROW(illumination_detail(c.points, c.irradiance, short_list), std::invalid_argument);
  EXPECT_THROW(illumination_detail(c.points, c.irradiance, c.variance, 20), std::invalid_argument);
  EXPECT_THROW(illumination_detail(c.points, c.irradiance, c.variance, 0), std::invalid_argument);
  EXPECT_NO_THROW(illumination_detail(c.points, c.irradiance, c.variance, 19));
}

TEST(IlluminationDetail, NextCountGrowsByTheSquaredRatioWithinItsBounds) {
  EXPECT_EQ(next_point_count(1000, 0.019, 0.02, 250000), 1000u);    // resolved
  EXPECT_EQ(next_point_count(1000, 0.02, 0.02, 250000), 1000u);     // exactly at the tolerance
  EXPECT_EQ(next_point_count(1000, 0.06, 0.02, 250000), 9000u);     // (0.06 / 0.02)^2 = 9
  EXPECT_EQ(next_point_count(1000, 0.021, 0.02, 250000), 2000u);    // at least 2x a round
  EXPECT_EQ(next_point_count(1000, 1.0, 0.02, 250000), 16000u);     // at most 16x a round
  EXPECT_EQ(next_point_count(100000, 1.0, 0.02, 250000), 250000u);  // never beyond the cap
  EXPECT_EQ(next_point_count(250000, 1.0, 0.02, 250000), 250000u);  // at the cap: stays
  EXPECT_EQ(pilot_point_count(250000), 3906u);
  EXPECT_EQ(pilot_point_count(20000), 1024u);
  EXPECT_EQ(pilot_point_count(600), 600u);
}

}  // namespace
}  // namespace dermis::sss::pointcloud
