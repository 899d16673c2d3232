#include "dermis/render/subsurface/heterogeneous_walk.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "dermis/sss/walk/analytic_boundaries.h"
#include "support/rgb_estimate.h"

namespace dermis {
namespace {

using Estimate = testing::RgbEstimate;
const auto estimate = testing::estimate_rgb;

// A density grid over the box [-1.2, 1.2]^3 around the unit ball. Its samples sit at the
// cells' centres, as pbrt-v4's, and between the outermost ones and the box the interpolation
// fades to zero: a grid of n >= 6 samples a side is constant over the ball when its samples are.
GridMedium density_grid(int n, const std::function<float(int, int, int)>& density) {
  GridMedium grid;
  grid.kind = GridMedium::Kind::Density;
  std::vector<float> values;
  for (int z = 0; z < n; ++z)
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) values.push_back(density(x, y, z));
  grid.density = VoxelGrid<float>(n, n, n, make_shared_floats(values));
  grid.p0 = Vec3(-1.2f, -1.2f, -1.2f);
  grid.p1 = Vec3(1.2f, 1.2f, 1.2f);
  grid.build_majorants();
  return grid;
}

const Vec3 kEntry(0, 0, 1);
const Vec3 kInto = normalize(Vec3(0.3f, 0.1f, -1));

// In a grid of constant density, the walk by null collisions leaves the unit ball with the
// homogeneous walk's weight (sss::random_walk, classical flights): per channel, the mean
// exit weight and the mean exit height within 4 standard errors of the difference, with a
// chromatic medium (the channels' flights differ) and forward scattering.
TEST(HeterogeneousWalk, AConstantGridWalksAsTheHomogeneousMedium) {
  const GridMedium grid = density_grid(8, [](int, int, int) { return 1.0f; });
  const RGB sigma_a(0.1f, 0.4f, 1.0f), sigma_s(3, 2, 1);
  const GridMediumView view{&grid, sigma_a, sigma_s, 0.4f, nullptr, false, RGB(0)};
  sss::WalkMedium homogeneous{sigma_s, sigma_a + sigma_s, 0.4f};
  sss::WalkSettings settings;
  settings.sampling = sss::WalkSampling::Classical;
  const sss::SphereTracer ball;
  constexpr int n = 160000;
  auto exit_value = [](bool left, const sss::WalkResult& r, bool height) {
    if (!left) return RGB(0);
    return height ? r.weight * (r.exit_p.z + 1) : r.weight;
  };
  for (const bool height : {false, true}) {
    SCOPED_TRACE(height ? "exit height" : "exit weight");
    Rng a(21, 1), b(22, 2);
    const Estimate het = estimate(n, [&] {
      sss::WalkResult r;
      RGB emitted;
      const bool left = heterogeneous_walk(view, settings, kEntry, kInto, a, ball, r, RGB(1), emitted);
      return exit_value(left, r, height);
    });
    const sss::MixtureWalkStep<3> step = sss::make_walk_step(homogeneous, settings);
    const Estimate hom = estimate(n, [&] {
      sss::WalkResult r;
      const bool left = sss::random_walk(step, settings, kEntry, Vec3(0, 0, 1), kInto, b, ball, r);
      return exit_value(left, r, height);
    });
    for (int c = 0; c < 3; ++c)
      EXPECT_LE(std::abs(het.mean[c] - hom.mean[c]), 4 * std::hypot(het.se[c], hom.se[c]))
          << "channel " << c << ": " << het.mean[c] << " vs " << hom.mean[c];
  }
}

// A purely absorbing, varying grid: every walk goes straight through, and its mean weight is
// the transmittance along the chord, exp(-optical depth) by quadrature, per channel.
TEST(HeterogeneousWalk, AnAbsorbingGridPassesItsTransmittance) {
  const GridMedium grid = density_grid(5, [](int x, int y, int z) { return float((x * 7 + y * 3 + z * 5) % 4); });
  const GridMediumView view{&grid, RGB(0.2f, 0.6f, 1.1f), RGB(0), 0, nullptr, false, RGB(0)};
  const sss::SphereTracer ball;
  const sss::BoundaryHit far = ball(kEntry, kInto);
  ASSERT_TRUE(far.hit);
  constexpr int steps = 200000;
  double tau[3] = {0, 0, 0};
  for (int i = 0; i < steps; ++i) {
    const double h = double(far.t) / steps;
    const MediumCoefficients k = view.at(kEntry + kInto * float((i + 0.5) * h));
    for (int c = 0; c < 3; ++c) tau[c] += double(k.sigma_a[c]) * h;
  }
  sss::WalkSettings settings;
  Rng rng(23, 3);
  const Estimate e = estimate(100000, [&] {
    sss::WalkResult r;
    RGB emitted;
    if (!heterogeneous_walk(view, settings, kEntry, kInto, rng, ball, r, RGB(1), emitted)) return RGB(0);
    EXPECT_EQ(r.steps, 0);
    return r.weight;
  });
  for (int c = 0; c < 3; ++c)
    EXPECT_LE(std::abs(e.mean[c] - std::exp(-tau[c])), 4 * e.se[c] + 1e-6)
        << "channel " << c << ": " << e.mean[c] << " vs " << std::exp(-tau[c]);
}

// A walk that starts with one channel carries that channel alone; one with no throughput,
// or no boundary ahead, does not leave; the step cap truncates.
TEST(HeterogeneousWalk, EdgeCases) {
  const GridMedium grid = density_grid(2, [](int, int, int) { return 1.0f; });
  const GridMediumView view{&grid, RGB(0.01f), RGB(5), 0, nullptr, false, RGB(0)};
  const sss::SphereTracer ball;
  sss::WalkSettings settings;
  Rng rng(24, 4);
  sss::WalkResult r;
  RGB emitted;
  for (int i = 0; i < 100; ++i)
    if (heterogeneous_walk(view, settings, kEntry, kInto, rng, ball, r, RGB(0, 1, 0), emitted)) {
      EXPECT_EQ(r.weight[0], 0);
      EXPECT_EQ(r.weight[2], 0);
    }
  EXPECT_FALSE(heterogeneous_walk(view, settings, kEntry, kInto, rng, ball, r, RGB(0), emitted));
  auto nowhere = [](Vec3, Vec3, double) { return sss::BoundaryHit{}; };
  EXPECT_FALSE(heterogeneous_walk(view, settings, kEntry, kInto, rng, nowhere, r, RGB(1), emitted));
  settings.max_steps = 0;
  int truncated = 0;
  for (int i = 0; i < 100; ++i)
    if (!heterogeneous_walk(view, settings, kEntry, kInto, rng, ball, r, RGB(1), emitted) && r.truncated) ++truncated;
  EXPECT_GT(truncated, 50);  // sigma_t = 5 across a chord of ~2: nearly every walk scatters
  EXPECT_EQ(emitted.max(), 0.0f);
}

}  // namespace
}  // namespace dermis
