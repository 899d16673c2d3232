#include "dermis/materials/grid_medium.h"

#include <gtest/gtest.h>

#include <vector>

#include "dermis/core/rng.h"
#include "dermis/materials/noise.h"
#include "dermis/spectral/spectrum_at.h"

namespace dermis {
namespace {

// pbrt-v4's SampledGrid: samples at cell centres, trilinear between them, zero beyond.
TEST(VoxelGrid, ReadsAsPbrtV4sSampledGrid) {
  VoxelGrid<float> g(4, 2, 1, make_shared_floats({1, 2, 3, 4, 10, 20, 30, 40}));
  EXPECT_FLOAT_EQ(g.lookup(Vec3(0.125f, 0.25f, 0.5f)), 1);   // sample (0, 0, 0)
  EXPECT_FLOAT_EQ(g.lookup(Vec3(0.625f, 0.75f, 0.5f)), 30);  // sample (2, 1, 0): x fastest
  EXPECT_FLOAT_EQ(g.lookup(Vec3(0.25f, 0.25f, 0.5f)), 1.5f);
  EXPECT_FLOAT_EQ(g.lookup(Vec3(0.125f, 0.5f, 0.5f)), 5.5f);
  EXPECT_FLOAT_EQ(g.lookup(Vec3(0.0f, 0.25f, 0.5f)), 0.5f);    // half way to the zero outside
  EXPECT_FLOAT_EQ(g.lookup(Vec3(0.125f, 0.25f, 0.0f)), 0.5f);  // likewise along z (one sample)
  EXPECT_FLOAT_EQ(g.lookup(Vec3(1.2f, 0.25f, 0.5f)), 0.0f);    // beyond the grid
  auto value = [](float v) { return v; };
  EXPECT_FLOAT_EQ(g.max_over(Vec3(0, 0, 0), Vec3(0.1f, 0.2f, 1), value), 1);   // only sample (0, 0) reaches it
  EXPECT_FLOAT_EQ(g.max_over(Vec3(0, 0, 0), Vec3(0.2f, 0.3f, 1), value), 20);  // samples (0..1, 0..1)
}

GridMedium density_medium(VoxelGrid<float> d) {
  GridMedium m;
  m.kind = GridMedium::Kind::Density;
  m.density = std::move(d);
  m.p0 = Vec3(-1, 0, 2);
  m.p1 = Vec3(2, 1, 2.5f);
  m.medium_from_world = (Transform::translate(Vec3d(0.3, -0.2, 1)) * Transform::rotate(30, Vec3d(1, 2, 3))).inverse();
  m.build_majorants();
  return m;
}

VoxelGrid<float> random_density(int nx, int ny, int nz, uint64_t seed) {
  std::vector<float> values;
  Rng rng(seed, 1);
  for (int i = 0; i < nx * ny * nz; ++i) values.push_back(rng.uniform() < 0.3f ? 0.0f : 3 * rng.uniform());
  return VoxelGrid<float>(nx, ny, nz, make_shared_floats(values));
}

// Every point of the box reads at most its majorant cell's value, in every slot, for a
// density grid, for an rgbgrid in RGB, and for an rgbgrid at any wavelengths.
TEST(GridMedium, MajorantsBoundTheCoefficients) {
  const GridMedium dens = density_medium(random_density(23, 7, 40, 3));
  GridMedium rgb = dens;
  rgb.kind = GridMedium::Kind::RGBGrid;
  rgb.density = {};
  Rng rng(4, 2);
  std::vector<float> sigma_a, sigma_s;  // three floats per sample
  for (int i = 0; i < 9 * 5 * 3; ++i) {
    const RGB a(rng.uniform(), 0.2f * rng.uniform(), 2 * rng.uniform());
    const RGB s(3 * rng.uniform(), rng.uniform(), 0);
    sigma_a.insert(sigma_a.end(), a.c, a.c + 3);
    sigma_s.insert(sigma_s.end(), s.c, s.c + 3);
  }
  rgb.sigma_a_grid = VoxelGrid<RGB>(9, 5, 3, make_shared_floats(sigma_a));
  rgb.sigma_s_grid = VoxelGrid<RGB>(9, 5, 3, make_shared_floats(sigma_s));
  rgb.build_majorants();
  SampledWavelengths w = SampledWavelengths::sample_visible(0.3f);
  const GridMediumView views[] = {{&dens, RGB(0.5f, 1, 2), RGB(1, 0.1f, 3), 0, nullptr},
                                  {&rgb, RGB(1.5f), RGB(1.5f), 0, nullptr},
                                  {&rgb, RGB(1.5f), RGB(1.5f), 0, &w}};
  for (const GridMediumView& v : views)
    for (int i = 0; i < 20000; ++i) {
      const Vec3 u(rng.uniform(), rng.uniform(), rng.uniform());
      const GridMedium& g = *v.grid;
      const Vec3 local = g.p0 + Vec3(u.x * (g.p1.x - g.p0.x), u.y * (g.p1.y - g.p0.y), u.z * (g.p1.z - g.p0.z));
      const Vec3 world = g.medium_from_world.inverse().point(local);
      const MediumCoefficients k = v.at(world);
      const Vec3 unit = g.unit_point(world);
      int cell[3];
      for (int a = 0; a < 3; ++a) cell[a] = std::min(int(unit[a] * float(g.majorant_res[a])), g.majorant_res[a] - 1);
      const RGB maj = v.majorant((cell[2] * g.majorant_res[1] + cell[1]) * g.majorant_res[0] + cell[0]);
      for (int c = 0; c < 3; ++c) ASSERT_LE(k.sigma_a[c] + k.sigma_s[c], maj[c] * (1 + 1e-5f) + 1e-6f) << i;
    }
}

// A density grid uniform over part of its box (one value in a block of samples, random
// elsewhere, and random over its outer layer, where the grid's zero padding enters): the
// cells inside the block read their one value without a look-up, and everywhere, including
// at the cells' faces and at points a rounding away from them, density_at reads what the
// trilinear look-up reads (to float rounding: the interpolation of equal values).
TEST(GridMedium, UniformCellsReadTheirValueAsTheLookUpWould) {
  const int n = 48;
  std::vector<float> values;
  Rng rng(9, 3);
  for (int z = 0; z < n; ++z)
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) {
        const bool block = x >= 4 && x < 40 && y >= 2 && y < 47 && z >= 6 && z < 30;
        values.push_back(block ? 2.5f : 3 * rng.uniform());
      }
  const GridMedium g = density_medium(VoxelGrid<float>(n, n, n, make_shared_floats(values)));
  int uniform = 0;
  for (const GridMedium::MajorantCell& c : g.majorants) uniform += c.uniform >= 0;
  EXPECT_GT(uniform, 16 * 16 * 16 / 8);
  EXPECT_LT(uniform, 16 * 16 * 16 / 2);
  std::vector<Vec3> points;
  for (int i = 0; i < 50000; ++i) points.emplace_back(rng.uniform(), rng.uniform(), rng.uniform());
  for (int i = 0; i <= 16; ++i)  // on and beside the cells' faces
    for (float d : {-1e-7f, 0.0f, 1e-7f}) {
      const float f = std::clamp(float(i) / 16 + d, 0.0f, 1.0f);
      points.emplace_back(f, rng.uniform(), rng.uniform());
      points.emplace_back(rng.uniform(), f, rng.uniform());
      points.emplace_back(rng.uniform(), rng.uniform(), f);
    }
  for (const Vec3& u : points)
    ASSERT_NEAR(g.density_at(u), g.density.lookup(u), 1e-6f * std::max(1.0f, g.density.lookup(u)))
        << u.x << " " << u.y << " " << u.z;
}

// The cells a ray crosses: contiguous stretches from where it enters the box to where it
// leaves it (or t_max), each inside the cell whose majorant it carries.
TEST(GridMedium, TraversalVisitsTheCellsAlongTheRay) {
  const GridMedium g = density_medium(random_density(16, 16, 16, 5));
  const GridMediumView v{&g, RGB(1), RGB(0), 0, nullptr};
  Rng rng(6, 3);
  const Transform world_from_medium = g.medium_from_world.inverse();
  for (int i = 0; i < 500; ++i) {
    // From outside the box toward a point inside it.
    const Vec3 target = world_from_medium.point(g.p0 + Vec3(rng.uniform() * 3, rng.uniform(), rng.uniform() * 0.5f));
    const Vec3 o = target + Vec3(rng.uniform() - 0.5f, rng.uniform() - 0.5f, rng.uniform() - 0.5f) * 12.0f;
    const Ray ray{o, normalize(target - o)};
    const float t_max = i % 2 ? length(target - o) : std::numeric_limits<float>::infinity();
    MajorantTraversal cells(v, ray, t_max);
    MajorantSegment s;
    float last = -1;
    int n = 0;
    while (cells.next(s)) {
      ASSERT_LT(s.t0, s.t1 + 1e-6f);
      if (n++ > 0) ASSERT_NEAR(s.t0, last, 1e-5f * std::max(1.0f, last));
      last = s.t1;
      const Vec3 unit = g.unit_point(ray.o + ray.d * (0.5f * (s.t0 + s.t1)));
      int cell[3];
      for (int a = 0; a < 3; ++a) {
        ASSERT_GE(unit[a], -1e-4f);
        ASSERT_LE(unit[a], 1 + 1e-4f);
        cell[a] = std::clamp(int(unit[a] * 16), 0, 15);
      }
      if (s.t1 - s.t0 > 1e-4f) ASSERT_EQ(s.sigma_maj, v.majorant((cell[2] * 16 + cell[1]) * 16 + cell[0])) << i;
    }
    ASSERT_GT(n, 0) << i;  // the ray reaches a point of the box
    if (i % 2) ASSERT_NEAR(last, t_max, 1e-4f * t_max);
  }
}

// pbrt-v4's Noise and CloudMedium::Density, at points where the reference values were
// computed with pbrt-v4 (commit 5f7a6068: util/noise.cpp, media.h), built outside the repository.
TEST(GridMedium, CloudIsPbrtV4s) {
  struct Case {
    Vec3 p;
    float noise, cloud_1_1_5, cloud_2_05_3;
  };
  const Case cases[] = {{{0.1f, 0.2f, 0.3f}, -0.141070575f, 0.916688025f, 0.741179705f},
                        {{0.37f, 0.61f, 0.83f}, 0.196435496f, 0, 0.54001981f},
                        {{1.7f, -0.4f, 2.2f}, -0.051298324f, 1, 1},
                        {{0.55f, 0.9f, 0.12f}, 0.326143652f, 0.182259247f, 0.156100109f},
                        {{-3.3f, 0.7f, 5.1f}, 0.479435742f, 0, 0.381672621f},
                        {{12.25f, 0.45f, -7.5f}, -0.164334953f, 0.200919569f, 0.100000024f}};
  for (const Case& c : cases) {
    EXPECT_NEAR(perlin_noise_pbrt_v4(c.p * 3.1f), c.noise, 2e-6f);
    EXPECT_NEAR(pbrt_v4_cloud_density(c.p, 1, 1, 5), c.cloud_1_1_5, 2e-5f);
    EXPECT_NEAR(pbrt_v4_cloud_density(c.p, 2, 0.5f, 3), c.cloud_2_05_3, 2e-5f);
  }
}

}  // namespace
}  // namespace dermis
