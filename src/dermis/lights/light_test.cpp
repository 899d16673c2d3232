#include "dermis/lights/light.h"

#include <gtest/gtest.h>

#include <cmath>

#include "dermis/core/rng.h"
#include "dermis/geometry/shape.h"
#include "support/chi_square.h"

namespace dermis {
namespace {

// A lat-long map with structure: a bright sun-like spot, a brighter band, a dark pole.
EnvironmentMap structured_map(const Transform& xf) {
  const int w = 64, h = 32;
  std::vector<float> px(std::size_t(w) * h * 3);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      float v = 0.2f + (y > 12 && y < 18 ? 1.0f : 0.0f) + (std::abs(x - 40) < 3 && std::abs(y - 8) < 3 ? 50.0f : 0.0f);
      if (y < 2) v = 0;
      for (int c = 0; c < 3; ++c) px[3 * (std::size_t(y) * w + x) + c] = v * (1 + 0.1f * c);
    }
  return EnvironmentMap(w, h, px, xf, 1.0f, EnvironmentMap::Mapping::LatLong);
}

TEST(EnvironmentMap, PdfIntegratesToOne) {
  EnvironmentMap env = structured_map(Transform::rotate(30, {1, 0, 0}));
  // Integrate in the map's own (u, v) parameterisation, where it is piecewise constant:
  // dω = 2π² sin θ du dv.
  const int nu = 512, nv = 256;
  double sum = 0;
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i) {
      Vec2 uv{(i + 0.5f) / nu, (j + 0.5f) / nv};
      Vec3 w = env.uv_to_direction(uv);
      sum += env.pdf(w) * 2 * kPi * kPi * std::sin(uv.y * kPi) / (double(nu) * nv);
    }
  // Midpoint rule on a 4x finer grid than the texels: error well below 1e-3.
  EXPECT_NEAR(sum, 1.0, 1e-3);
}

TEST(EnvironmentMap, SamplerMatchesPdfChiSquare) {
  // Rotated map; samples are binned in the map's own (phi, theta) grid, one bin per
  // texel, where the target density is known exactly: a texel's probability is its
  // luminance times sin(theta at its centre) over the sum (dω = 2π² sin θ du dv).
  const Transform xf = Transform::rotate(30, {1, 0, 0});
  EnvironmentMap env = structured_map(xf);
  const int w = 64, h = 32, n = 400000;
  std::vector<double> observed(w * h, 0), expected(w * h, 0);
  Rng rng(11, 12);
  int pdf_mismatches = 0;
  for (int i = 0; i < n; ++i) {
    float pdf;
    Vec3 dir = env.sample({rng.uniform(), rng.uniform()}, &pdf);
    ASSERT_GT(pdf, 0);
    // Float round-off can move a direction across a texel edge; count, don't fail.
    if (std::abs(pdf / env.pdf(dir) - 1) > 0.01f) ++pdf_mismatches;
    Vec3 l = normalize(xf.inverse().vector(dir));
    double theta = std::acos(std::clamp(double(l.z), -1.0, 1.0)), phi = std::atan2(l.y, l.x);
    if (phi < 0) phi += 2 * kPiD;
    int x = std::clamp(int(phi / (2 * kPiD) * w), 0, w - 1), y = std::clamp(int(theta / kPiD * h), 0, h - 1);
    observed[y * w + x] += 1;
  }
  EXPECT_LT(pdf_mismatches, n / 1000);
  EnvironmentMap plain = structured_map(Transform());
  double total = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      Vec3 d = plain.uv_to_direction({(x + 0.5f) / w, (y + 0.5f) / h});
      total += expected[y * w + x] = plain.eval(d).luminance() * std::sin((y + 0.5) / h * kPiD);
    }
  for (double& e : expected) e *= n / total;
  auto r = testing::chi_square(observed, expected);
  EXPECT_GT(r.p_value, testing::kChiSquareAlpha) << "chi2 " << r.statistic << " dof " << r.dof;
}

TEST(EnvironmentMap, EvalMatchesTexelsAlongTheMapping) {
  EnvironmentMap env = structured_map(Transform());
  // The sun texel (x=40, y=8) seen from its direction.
  Vec3 w = env.uv_to_direction({(40 + 0.5f) / 64, (8 + 0.5f) / 32});
  EXPECT_NEAR(env.eval(w)[0], 50.2f, 1e-4);
  // +z is the top row (dark pole here).
  EXPECT_EQ(env.eval({0, 0, 1})[0], 0.0f);
}

TEST(Light, TrianglePdfMatchesSampledDensity) {
  Shape s;
  s.positions = {{0, 0, 2}, {1, 0, 2}, {0, 1, 2.5f}};
  s.indices = {0, 1, 2};
  Light l;
  l.type = Light::Type::Triangle;
  l.p0 = s.positions[0];
  l.p1 = s.positions[1];
  l.p2 = s.positions[2];
  l.area = 0.5f * length(cross(l.p1 - l.p0, l.p2 - l.p0));
  l.shape = 0;
  l.prim = 0;
  l.two_sided = true;
  l.emission = RGB(1);
  std::vector<Shape> shapes{s};
  Rng rng(1, 1);
  Vec3 ref{0.2f, 0.1f, 0};
  // The estimator of the solid angle subtended, E[1/pdf], against a fine quadrature.
  double est = 0;
  const int n = 100000;
  for (int i = 0; i < n; ++i) {
    LightSample ls;
    ASSERT_TRUE(light_sample(l, shapes, ref, {rng.uniform(), rng.uniform()}, ls));
    EXPECT_NEAR(ls.pdf, light_pdf(l, ref, ls.wi, ls.p_light, ls.n_light), 1e-3f * ls.pdf);
    est += 1.0 / ls.pdf;
  }
  est /= n;
  // Solid angle of a triangle (Van Oosterom & Strackee 1983).
  Vec3d a = Vec3d(l.p0 - ref), b = Vec3d(l.p1 - ref), c = Vec3d(l.p2 - ref);
  double la = length(a), lb = length(b), lc = length(c);
  double omega =
      2 * std::atan2(std::abs(dot(a, cross(b, c))), la * lb * lc + dot(a, b) * lc + dot(a, c) * lb + dot(b, c) * la);
  EXPECT_NEAR(est, omega, 1e-3 * omega);
}

// With a surface normal, a uniform sky is sampled by the cosine about it: the pdf that
// light_pdf() reports matches, every direction is above the surface, and the estimate
// of the irradiance pi L has no variance.
TEST(Light, UniformSkyAtASurfaceIsSampledByTheCosine) {
  Light l;
  l.type = Light::Type::Infinite;
  l.emission = RGB(0.5f);
  std::vector<Shape> shapes;
  const Vec3 n = normalize(Vec3(0.3f, -0.2f, 0.9f));
  Rng rng(3, 3);
  for (int i = 0; i < 10000; ++i) {
    LightSample ls;
    ASSERT_TRUE(light_sample(l, shapes, {0, 0, 0}, {rng.uniform(), rng.uniform()}, ls, n));
    EXPECT_GT(dot(ls.wi, n), 0.0f);
    EXPECT_NEAR(ls.pdf, light_pdf(l, {0, 0, 0}, ls.wi, {}, {}, n), 1e-5f * ls.pdf);
    EXPECT_NEAR(ls.L[0] * dot(ls.wi, n) / ls.pdf, kPi * 0.5f, 1e-3f);  // irradiance, every sample
  }
  // Without a normal (a point in a medium): uniform over the sphere.
  LightSample ls;
  ASSERT_TRUE(light_sample(l, shapes, {0, 0, 0}, {0.3f, 0.6f}, ls));
  EXPECT_FLOAT_EQ(ls.pdf, 1 / (4 * kPi));
  EXPECT_FLOAT_EQ(light_pdf(l, {0, 0, 0}, ls.wi, {}, {}), 1 / (4 * kPi));
}

TEST(Light, SphereConeSamplingCoversTheSubtendedSolidAngle) {
  Light l;
  l.type = Light::Type::Sphere;
  l.center = {0, 0, 3};
  l.radius = 1;
  l.emission = RGB(1);
  std::vector<Shape> shapes;
  Rng rng(2, 2);
  for (int i = 0; i < 10000; ++i) {
    LightSample ls;
    ASSERT_TRUE(light_sample(l, shapes, {0, 0, 0}, {rng.uniform(), rng.uniform()}, ls));
    EXPECT_NEAR(length(ls.p_light - l.center), 1, 1e-4);
    EXPECT_GT(dot(ls.n_light, -ls.wi), -1e-4);  // the visible cap only
    // 1/pdf is the solid angle 2π(1 - cos θmax) exactly.
    EXPECT_NEAR(1 / ls.pdf, 2 * kPi * (1 - std::sqrt(1 - 1.0f / 9)), 1e-4);
  }
}

}  // namespace
}  // namespace dermis
