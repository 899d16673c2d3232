#include "dermis/sss/pointcloud/irradiance_octree.h"

#include <gtest/gtest.h>

#include <cstdio>

#include "dermis/core/rng.h"

namespace dermis::sss::pointcloud {
namespace {

struct Cloud {
  std::vector<SurfacePoint> points;
  std::vector<RGB> irradiance;
};

// n random points: on the plane z = 0 (flat) or in a box (volume), random areas and RGB
// irradiance, so that the centroids differ per channel.
Cloud random_cloud(std::size_t n, bool flat, uint64_t seed) {
  Cloud c;
  Rng rng(seed, 1);
  for (std::size_t i = 0; i < n; ++i) {
    SurfacePoint s;
    s.position = {2 * rng.uniform(), 2 * rng.uniform(), flat ? 0.0f : 2 * rng.uniform()};
    s.normal = {0, 0, 1};
    s.area = (0.5f + rng.uniform()) * 4.0f / float(n);
    c.points.push_back(s);
    c.irradiance.push_back(RGB(rng.uniform(), 2 * rng.uniform(), rng.uniform() * rng.uniform()));
  }
  return c;
}

double max_relative_error(RGB a, RGB ref) {
  double e = 0;
  for (int c = 0; c < 3; ++c) e = std::max(e, std::abs(double(a[c]) - ref[c]) / std::abs(double(ref[c])));
  return e;
}

// M(x) with the hierarchy converges to the sum over every point as epsilon -> 0.
TEST(IrradianceOctree, ConvergesToBruteForceAsEpsilonShrinks) {
  const ProfileRGB profile = make_dipole_rgb(RGB(0.8f, 0.6f, 0.4f), RGB(0.2f, 0.1f, 0.05f), 1.3);
  const double eps[] = {1.0, 0.3, 0.1, 0.03, 0.01, 0.001, 0.0};
  for (bool flat : {true, false}) {
    const Cloud c = random_cloud(20000, flat, flat ? 5 : 6);
    const IrradianceOctree tree(c.points, c.irradiance);
    double area = 0;
    for (const auto& p : c.points) area += p.area;
    EXPECT_NEAR(tree.total_area(), area, 1e-5 * area);
    Rng rng(9, flat);
    std::vector<Vec3> xs;
    for (int q = 0; q < 20; ++q) xs.push_back({2 * rng.uniform(), 2 * rng.uniform(), flat ? 0.0f : 2 * rng.uniform()});
    double previous = 1e30;
    for (double e : eps) {
      double worst = 0;
      for (const Vec3& x : xs)
        worst = std::max(worst, max_relative_error(tree.query(x, profile, e), tree.brute_force(x, profile)));
      std::printf("%s eps %-6g max relative error %.2e\n", flat ? "plane" : "box  ", e, worst);
      EXPECT_LE(worst, previous * 1.05 + 1e-6) << "eps " << e;
      previous = worst;
      if (e <= 0.001) {
        EXPECT_LT(worst, 1e-3);
      }
      if (e == 0.0) {
        EXPECT_LT(worst, 1e-5);  // every leaf summed point by point
      }
    }
  }
}

TEST(IrradianceOctree, StatisticsAndBadInput) {
  const Cloud c = random_cloud(1000, true, 3);
  const IrradianceOctree tree(c.points, c.irradiance);
  EXPECT_EQ(tree.point_count(), 1000u);
  EXPECT_GT(tree.node_count(), 1000u / 8);
  EXPECT_GE(tree.memory_bytes(), 1000u * 28);
  std::vector<RGB> bad = c.irradiance;
  bad[5] = RGB(-1.0f);
  EXPECT_THROW(IrradianceOctree(c.points, bad), std::invalid_argument);
  EXPECT_THROW(IrradianceOctree(c.points, std::span<const RGB>(c.irradiance).first(10)), std::invalid_argument);
  EXPECT_THROW(IrradianceOctree({}, {}), std::invalid_argument);
  // Coincident points do not recurse forever.
  std::vector<SurfacePoint> same(100, c.points[0]);
  const IrradianceOctree one(same, std::vector<RGB>(100, RGB(1.0f)));
  EXPECT_EQ(one.node_count(), 1u);
}

}  // namespace
}  // namespace dermis::sss::pointcloud
