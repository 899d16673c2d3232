#include "dermis/sss/walk/monotone_hermite.h"

#include <gtest/gtest.h>

#include <random>
#include <vector>

namespace dermis::sss {
namespace {

// Random non-increasing nodes on [0, 1] with Fritsch-Butland slopes (as AlbedoInversion
// makes them), every third interval flat.
std::vector<HermiteNode> random_nodes(std::mt19937& rng, int n) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<HermiteNode> nodes(static_cast<std::size_t>(n));
  double y = 1;
  for (int i = 0; i < n; ++i) {
    if (i > 0 && i % 3 != 0) y -= u(rng) / n;
    nodes[static_cast<std::size_t>(i)] = {double(i) / (n - 1), y, 0};
  }
  for (int i = 0; i < n; ++i) {
    const double h = 1.0 / (n - 1);
    const double left = i > 0 ? (nodes[i].y - nodes[i - 1].y) / h : (nodes[1].y - nodes[0].y) / h;
    const double right = i + 1 < n ? (nodes[i + 1].y - nodes[i].y) / h : left;
    nodes[std::size_t(i)].m = left * right > 0 ? 2 * left * right / (left + right) : 0.0;
  }
  return nodes;
}

double value_at(const std::vector<HermiteNode>& nodes, double t) {
  const int n = int(nodes.size());
  const int k = std::min(n - 2, int(t * (n - 1)));
  return hermite_between(nodes[std::size_t(k)], nodes[std::size_t(k) + 1], t);
}

// sup{t : A(t) > level} by bisection on the interpolant's values alone.
double bisection(const std::vector<HermiteNode>& nodes, double level) {
  double lo = 0, hi = 1;
  if (!(value_at(nodes, 0) > level)) return 0;
  if (value_at(nodes, 1) > level) return 1;
  for (int i = 0; i < 200 && hi - lo > 1e-16; ++i) {
    const double mid = 0.5 * (lo + hi);
    (value_at(nodes, mid) > level ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

TEST(MonotoneHermite, InterpolatesTheNodesAndDifferentiates) {
  std::mt19937 rng(3);
  const std::vector<HermiteNode> nodes = random_nodes(rng, 9);
  for (std::size_t k = 0; k + 1 < nodes.size(); ++k) {
    double slope;
    EXPECT_EQ(hermite_between(nodes[k], nodes[k + 1], nodes[k].t, &slope), nodes[k].y);
    EXPECT_NEAR(slope, nodes[k].m, 1e-12);
    EXPECT_NEAR(hermite_between(nodes[k], nodes[k + 1], nodes[k + 1].t, &slope), nodes[k + 1].y, 1e-15);
    EXPECT_NEAR(slope, nodes[k + 1].m, 1e-12);
    for (double s : {0.1, 0.37, 0.8}) {
      const double t = nodes[k].t + s * (nodes[k + 1].t - nodes[k].t), dt = 1e-6;
      hermite_between(nodes[k], nodes[k + 1], t, &slope);
      const double fd =
          (hermite_between(nodes[k], nodes[k + 1], t + dt) - hermite_between(nodes[k], nodes[k + 1], t - dt)) /
          (2 * dt);
      EXPECT_NEAR(slope, fd, 1e-6) << k << " " << s;
    }
  }
}

// The crossing against bisection on the values. Where the interpolant falls steadily
// they agree to double precision; at the edge of a flat part the cubic meets the level
// with slope 0 and both pin t only to about 1e-8: there the value at the answer is
// checked instead.
TEST(MonotoneHermite, CrossingIsTheBisectionsAnswer) {
  std::mt19937 rng(7);
  for (int trial = 0; trial < 20; ++trial) {
    const std::vector<HermiteNode> nodes = random_nodes(rng, 4 + trial % 30);
    auto node = [&](int k) { return nodes[std::size_t(k)]; };
    for (int i = -1; i <= 1001; ++i) {
      const double level = i / 1000.0;
      const double t = crossing_of_non_increasing(int(nodes.size()), node, level);
      EXPECT_NEAR(t, bisection(nodes, level), 1e-7) << trial << " " << level;
      // Just before the answer A exceeds the level, at it A does not (within rounding),
      // unless A exceeds it everywhere (t = 1).
      if (level >= nodes.back().y) {
        EXPECT_LE(value_at(nodes, t), level + 1e-14) << trial << " " << level;
      }
      if (t > 1e-6) {
        EXPECT_GT(value_at(nodes, t - 1e-6), level - 1e-14) << trial << " " << level;
      }
    }
    // Levels at the nodes: a node's own t, or where a flat part at that level starts. (A
    // flat part's cubic rounds to its level plus or minus an ulp, so bisection on its
    // values lands anywhere on it: checked by the values instead.)
    for (const HermiteNode& n : nodes) {
      const double t = crossing_of_non_increasing(int(nodes.size()), node, n.y);
      EXPECT_NEAR(value_at(nodes, t), n.y, 1e-14) << trial;
      EXPECT_LE(t, n.t + 1e-12) << trial;
      if (t > 1e-6) {
        EXPECT_GT(value_at(nodes, t - 1e-6), n.y) << trial;
      }
    }
  }
}

// Newton converges in a few steps where the cubic falls steadily, t near 1 included (a
// stopping rule finer than t's ulp there once made it take all 100).
TEST(MonotoneHermite, ConvergesInAFewSteps) {
  std::vector<HermiteNode> nodes;
  for (int i = 0; i <= 31; ++i) {  // A = (1 - t)(2 - t)/2: falling, slope (2t - 3)/2 < 0 throughout
    const double t = i / 31.0;
    nodes.push_back({t, (1 - t) * (2 - t) / 2, (2 * t - 3) / 2});
  }
  auto node = [&](int k) { return nodes[std::size_t(k)]; };
  int most = 0;
  for (int i = 1; i < 100000; ++i) {
    const double level = i / 100000.0;
    int steps = 0;
    const double t = crossing_of_non_increasing(int(nodes.size()), node, level, &steps);
    EXPECT_NEAR(value_at(nodes, t), level, 1e-13) << level;
    EXPECT_LE(steps, 8) << level;
    most = std::max(most, steps);
  }
  EXPECT_LE(most, 8);
}

}  // namespace
}  // namespace dermis::sss
