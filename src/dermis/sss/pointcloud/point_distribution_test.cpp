#include "dermis/sss/pointcloud/point_distribution.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "dermis/sss/pointcloud/point_grid.h"

namespace dermis::sss::pointcloud {
namespace {

// A unit square (two triangles) and a 2 x 1 x 0.5 box (twelve triangles).
void square(std::vector<Vec3>& p, std::vector<uint32_t>& idx) {
  p = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  idx = {0, 1, 2, 0, 2, 3};
}
void box(std::vector<Vec3>& p, std::vector<uint32_t>& idx) {
  p.clear();
  for (int i = 0; i < 8; ++i) p.push_back({i & 1 ? 2.0f : 0.0f, i & 2 ? 1.0f : 0.0f, i & 4 ? 0.5f : 0.0f});
  idx = {0, 2, 1, 1, 2, 3, 4, 5, 6, 5, 7, 6, 0, 1, 4, 1, 5, 4, 2, 6, 3, 3, 6, 7, 0, 4, 2, 2, 4, 6, 1, 3, 5, 3, 7, 5};
}

std::vector<double> nearest_neighbour_distances(const std::vector<SurfacePoint>& pts) {
  std::vector<Vec3> pos;
  for (const auto& s : pts) pos.push_back(s.position);
  const PointGrid grid(pos, 0.05);
  std::vector<double> d;
  for (const Vec3& x : pos) d.push_back(grid.kth_nearest_distance(x, 2));  // k = 1 is the point itself
  return d;
}

TEST(PointDistribution, CountsAreasAndPointsOnTheirTriangles) {
  std::vector<Vec3> p;
  std::vector<uint32_t> idx;
  box(p, idx);
  const double area = mesh_area(p, idx);
  EXPECT_NEAR(area, 2 * (2 * 1 + 2 * 0.5 + 1 * 0.5), 1e-6);
  const auto pts = distribute_points(p, idx, 3000, 42);
  ASSERT_EQ(pts.size(), 3000u);
  double sum = 0;
  for (const auto& s : pts) {
    sum += s.area;
    const Vec3d a(p[idx[3 * s.triangle]]), b(p[idx[3 * s.triangle + 1]]), c(p[idx[3 * s.triangle + 2]]);
    const Vec3d n = normalize(cross(b - a, c - a)), x(s.position);
    EXPECT_NEAR(length(Vec3d(s.normal)), 1.0, 1e-6);
    EXPECT_NEAR(dot(Vec3d(s.normal), n), 1.0, 1e-6);
    EXPECT_NEAR(dot(x - a, n), 0.0, 1e-6);  // in the triangle's plane
    // Inside: the barycentric areas sum to the triangle's area.
    const double whole = length(cross(b - a, c - a));
    const double parts = length(cross(b - x, c - x)) + length(cross(c - x, a - x)) + length(cross(a - x, b - x));
    EXPECT_NEAR(parts, whole, 1e-5 * whole);
  }
  EXPECT_NEAR(sum, area, 1e-5 * area);
  EXPECT_EQ(point_count_for_density(area, 0.1, 2.0), std::ceil(area * 200 - 1e-9));
}

// Blue noise versus white noise on the unit square, N = 2000, r_max = sqrt(1/(2 sqrt3 N))
// (Yuksel 2015, eq. 5) = 0.0120: half the spacing of a hexagonal packing of N points. White noise: P(nn < d) = 1 -
// exp(-pi N d^2), so 20 % of points have a neighbour closer than r_max / 2 and the smallest distance is tiny.
TEST(PointDistribution, BlueNoiseHasLargerNearestNeighbourDistances) {
  std::vector<Vec3> p;
  std::vector<uint32_t> idx;
  square(p, idx);
  const std::size_t n = 2000;
  const double r_max = std::sqrt(1.0 / (2 * std::sqrt(3.0) * double(n)));
  const auto blue = nearest_neighbour_distances(distribute_points(p, idx, n, 7));
  const auto white = nearest_neighbour_distances(uniform_random_points(p, idx, n, 7));
  auto stats = [&](const std::vector<double>& d, double* mn, double* mean, double* below) {
    *mn = *std::min_element(d.begin(), d.end());
    *mean = 0;
    *below = 0;
    for (double v : d) {
      *mean += v / double(d.size());
      *below += v < 0.5 * r_max ? 1.0 / double(d.size()) : 0.0;
    }
  };
  double bmin, bmean, bbelow, wmin, wmean, wbelow;
  stats(blue, &bmin, &bmean, &bbelow);
  stats(white, &wmin, &wmean, &wbelow);
  std::printf("nn/r_max: blue min %.3f mean %.3f below 0.5: %.4f | white min %.4f mean %.3f below 0.5: %.4f\n",
              bmin / r_max, bmean / r_max, bbelow, wmin / r_max, wmean / r_max, wbelow);
  // White-noise mean nn distance 0.5/sqrt(N) = 0.93 r_max (Clark & Evans 1954), a bit more
  // with the square's edges; fraction below r_max/2 = 1 - exp(-pi/(8 sqrt 3)) = 0.203,
  // binomial sigma 0.009.
  EXPECT_NEAR(wbelow, 1 - std::exp(-kPiD / (8 * std::sqrt(3.0))), 4 * 0.009 + 0.01);
  EXPECT_GT(bmin, r_max);  // no close pairs at all (hexagonal packing: 2 r_max)
  EXPECT_GT(bmin, 10 * wmin);
  EXPECT_GT(bmean, 1.3 * wmean);  // spread out
  EXPECT_EQ(bbelow, 0.0);
}

TEST(PointDistribution, DeterministicForASeed) {
  std::vector<Vec3> p;
  std::vector<uint32_t> idx;
  box(p, idx);
  const auto a = distribute_points(p, idx, 500, 3), b = distribute_points(p, idx, 500, 3),
             c = distribute_points(p, idx, 500, 4);
  ASSERT_EQ(a.size(), b.size());
  int same_as_c = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].position, b[i].position);
    same_as_c += a[i].position == c[i].position;
  }
  EXPECT_LT(same_as_c, 5);
}

// The progress callback sees the steps grow to distribution_steps() and the points do not
// depend on it; a callback that throws stops the distribution there.
TEST(PointDistribution, ReportsProgressAndStopsWhenTheCallbackThrows) {
  std::vector<Vec3> p;
  std::vector<uint32_t> idx;
  box(p, idx);
  DistributionOptions o;
  std::vector<std::size_t> seen;
  o.progress = [&](std::size_t done) { seen.push_back(done); };
  const auto with = distribute_points(p, idx, 3000, 5, o), without = distribute_points(p, idx, 3000, 5);
  ASSERT_EQ(with.size(), without.size());
  for (std::size_t i = 0; i < with.size(); ++i) ASSERT_EQ(with[i].position, without[i].position);
  ASSERT_GE(seen.size(), 5u);  // 15000 candidates weighed, 12000 eliminated: several calls each
  EXPECT_TRUE(std::is_sorted(seen.begin(), seen.end()));
  EXPECT_EQ(seen.back(), distribution_steps(3000));
  EXPECT_EQ(distribution_steps(3000), 15000u + 15000u + 12000u);

  struct Stop {};
  int calls = 0;
  o.progress = [&](std::size_t done) {
    ++calls;
    if (done > 20000) throw Stop{};
  };
  EXPECT_THROW(distribute_points(p, idx, 3000, 5, o), Stop);
  EXPECT_LT(calls, int(seen.size()));
}

TEST(PointDistribution, BadInputIsRejected) {
  std::vector<Vec3> p;
  std::vector<uint32_t> idx;
  square(p, idx);
  EXPECT_THROW(distribute_points(p, idx, 0, 1), std::invalid_argument);
  EXPECT_THROW(distribute_points(p, {0, 1}, 10, 1), std::invalid_argument);
  EXPECT_THROW(distribute_points(p, {0, 1, 9}, 10, 1), std::invalid_argument);
  EXPECT_THROW(distribute_points(p, {0, 0, 1}, 10, 1), std::invalid_argument);  // no area
  EXPECT_THROW(point_count_for_density(1.0, 0.0, 1.0), std::invalid_argument);
}

}  // namespace
}  // namespace dermis::sss::pointcloud
