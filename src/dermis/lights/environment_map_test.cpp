// pbrt-v4's equal-area octahedral environment maps (Clarberg 2008).
#include "dermis/lights/environment_map.h"

#include <gtest/gtest.h>

#include <cmath>

#include "dermis/core/rng.h"
#include "dermis/core/warp.h"
#include "support/chi_square.h"

namespace dermis {
namespace {

TEST(EqualAreaMapping, RoundTripsAndKnowsItsLandmarks) {
  // Centre +z, corners -z, edge midpoints on the equator along +-x, +-y.
  EXPECT_NEAR(equal_area_square_to_sphere({0.5f, 0.5f}).z, 1, 1e-6);
  EXPECT_NEAR(equal_area_square_to_sphere({0, 0}).z, -1, 1e-6);
  EXPECT_NEAR(equal_area_square_to_sphere({1, 0.5f}).x, 1, 1e-6);
  EXPECT_NEAR(equal_area_square_to_sphere({0.5f, 1}).y, 1, 1e-6);
  Rng rng(3, 4);
  for (int i = 0; i < 10000; ++i) {
    const Vec2 uv{rng.uniform(), rng.uniform()};
    const Vec3 w = equal_area_square_to_sphere(uv);
    ASSERT_NEAR(length(w), 1, 1e-5);
    const Vec2 back = equal_area_sphere_to_square(w);
    ASSERT_NEAR(back.x, uv.x, 2e-4) << uv.x << " " << uv.y;
    ASSERT_NEAR(back.y, uv.y, 2e-4) << uv.x << " " << uv.y;
  }
}

// Equal area: uniform points of the square are uniform on the sphere. Binned by z in 16
// equal-area bands and by octant-free azimuth in 16 sectors: chi-square.
TEST(EqualAreaMapping, UniformSquareIsUniformSphere) {
  const int bands = 16, sectors = 16, n = 200000;
  std::vector<double> observed(bands * sectors, 0), expected(bands * sectors, double(n) / (bands * sectors));
  Rng rng(5, 6);
  for (int i = 0; i < n; ++i) {
    const Vec3 w = equal_area_square_to_sphere({rng.uniform(), rng.uniform()});
    double phi = std::atan2(w.y, w.x);
    if (phi < 0) phi += 2 * kPiD;
    const int b = std::clamp(int((w.z + 1) / 2 * bands), 0, bands - 1);
    const int s = std::clamp(int(phi / (2 * kPiD) * sectors), 0, sectors - 1);
    observed[b * sectors + s] += 1;
  }
  auto r = testing::chi_square(observed, expected);
  EXPECT_GT(r.p_value, testing::kChiSquareAlpha) << "chi2 " << r.statistic << " dof " << r.dof;
}

EnvironmentMap square_map(const Transform& xf) {
  const int s = 32;
  std::vector<float> px(std::size_t(s) * s * 3);
  for (int y = 0; y < s; ++y)
    for (int x = 0; x < s; ++x) {
      const float v = 0.2f + (std::abs(x - 20) < 3 && std::abs(y - 9) < 3 ? 40.0f : 0.0f) + (x < 4 ? 1.0f : 0.0f);
      for (int c = 0; c < 3; ++c) px[3 * (std::size_t(y) * s + x) + c] = v * (1 + 0.1f * c);
    }
  return EnvironmentMap(s, s, px, xf, 1.0f, EnvironmentMap::Mapping::EqualArea);
}

TEST(EqualAreaEnvironmentMap, PdfIntegratesToOneAndSamplerMatchesIt) {
  const Transform xf = Transform::rotate(30, {1, 0, 0});
  EnvironmentMap env = square_map(xf);
  // The pdf over the sphere, integrated in uv (dω = 4 π du dv), midpoint rule on a grid
  // 4x finer than the texels.
  const int g = 128;
  double sum = 0;
  for (int j = 0; j < g; ++j)
    for (int i = 0; i < g; ++i)
      sum += env.pdf(env.uv_to_direction({(i + 0.5f) / g, (j + 0.5f) / g})) * 4 * kPi / (g * g);
  EXPECT_NEAR(sum, 1.0, 1e-3);
  // Samples binned per texel: a texel's probability is its luminance over the sum (every
  // texel has the same solid angle).
  const int s = 32, n = 300000;
  std::vector<double> observed(s * s, 0), expected(s * s, 0);
  Rng rng(7, 8);
  for (int i = 0; i < n; ++i) {
    float pdf;
    const Vec3 dir = env.sample({rng.uniform(), rng.uniform()}, &pdf);
    ASSERT_GT(pdf, 0);
    const Vec2 uv = equal_area_sphere_to_square(normalize(xf.inverse().vector(dir)));
    observed[std::clamp(int(uv.y * s), 0, s - 1) * s + std::clamp(int(uv.x * s), 0, s - 1)] += 1;
  }
  double total = 0;
  for (int y = 0; y < s; ++y)
    for (int x = 0; x < s; ++x)
      total += expected[y * s + x] = env.eval(env.uv_to_direction({(x + 0.5f) / s, (y + 0.5f) / s})).luminance();
  for (double& e : expected) e *= n / total;
  auto r = testing::chi_square(observed, expected);
  EXPECT_GT(r.p_value, testing::kChiSquareAlpha) << "chi2 " << r.statistic << " dof " << r.dof;
}

// The one-look-up forms give what the separate ones give: eval(w, &pdf) is eval(w) and
// pdf(w) exactly; sample()'s radiance is eval's at the sampled direction and its density
// pdf()'s (read at the sampled point's pixel, which the direction maps back into but for float
// rounding at a pixel's edge: at most a few in a thousand). Both mappings.
TEST(EnvironmentMap, OneLookUpFormsAgreeWithTheSeparateOnes) {
  const Transform xf = Transform::rotate(30, {1, 0, 0});
  const int w = 32, h = 16;
  std::vector<float> px(std::size_t(w) * h * 3);
  Rng fill(3, 4);
  for (float& v : px) v = fill.uniform() < 0.1f ? 50 * fill.uniform() : fill.uniform();
  for (const EnvironmentMap& env :
       {square_map(xf), EnvironmentMap(w, h, px, xf, 2.0f, EnvironmentMap::Mapping::LatLong)}) {
    Rng rng(5, 6);
    int moved = 0;
    const int n = 20000;
    for (int i = 0; i < n; ++i) {
      const Vec3 d = sample_uniform_sphere({rng.uniform(), rng.uniform()});
      float pdf = -1;
      const RGB L = env.eval(d, &pdf);
      ASSERT_EQ(L, env.eval(d));
      ASSERT_EQ(pdf, env.pdf(d));
      float sampled_pdf;
      RGB sampled_L;
      const Vec3 s = env.sample({rng.uniform(), rng.uniform()}, &sampled_pdf, &sampled_L);
      // The density within 1e-4 (lat-long: the Jacobian sin(theta) at the sampled point and at
      // the direction's, which rounding sets apart by an ulp or so).
      if (sampled_L != env.eval(s) || std::abs(sampled_pdf - env.pdf(s)) > 1e-4f * sampled_pdf) ++moved;
    }
    EXPECT_LE(moved, n / 200);
  }
}

// The mean direction light arrives from: none for a uniform map; for radiance 1 with a cap
// of half-angle a about d at 1 + S, S pi sin^2(a) d over 4 pi + S 2 pi (1 - cos a) (the
// cap's integral of w dw is pi sin^2(a) d). Within 2 % in length and half a degree in
// direction: texels straddle the cap's rim. Both mappings, rotated into the world.
TEST(EnvironmentMap, MeanArrivalPointsAtTheSunWithItsShareOfTheLight) {
  const Transform xf = Transform::rotate(30, {1, 0, 0});
  const float a = 15 * kPi / 180, S = 50;
  const Vec3 d = normalize(Vec3(0.5f, 0.6f, 0.62f));  // light space
  const float expected = S * kPi * std::sin(a) * std::sin(a) / (4 * kPi + S * 2 * kPi * (1 - std::cos(a)));
  for (const auto mapping : {EnvironmentMap::Mapping::EqualArea, EnvironmentMap::Mapping::LatLong}) {
    const bool equal_area = mapping == EnvironmentMap::Mapping::EqualArea;
    const int w = equal_area ? 384 : 512, h = equal_area ? 384 : 256;
    std::vector<float> uniform(std::size_t(w) * h * 3, 1.0f), sun = uniform;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const Vec2 uv{(x + 0.5f) / w, (y + 0.5f) / h};
        const float theta = uv.y * kPi, phi = uv.x * 2 * kPi;  // lat-long, light space
        const Vec3 dir = equal_area
                             ? equal_area_square_to_sphere(uv)
                             : Vec3(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
        if (dot(dir, d) > std::cos(a))
          for (int c = 0; c < 3; ++c) sun[3 * (std::size_t(y) * w + x) + c] += S;
      }
    SCOPED_TRACE(equal_area ? "equal-area" : "lat-long");
    EXPECT_LT(length(EnvironmentMap(w, h, uniform, xf, 2.0f, mapping).mean_arrival()), 1e-3f);
    const Vec3 m = EnvironmentMap(w, h, sun, xf, 2.0f, mapping).mean_arrival();
    EXPECT_NEAR(length(m), expected, 0.02f * expected);
    EXPECT_GT(dot(normalize(m), normalize(xf.vector(d))), std::cos(0.5f * kPi / 180));
  }
}

TEST(EqualAreaEnvironmentMap, NonSquareImageIsAnErrorThatNamesLatLong) {
  try {
    EnvironmentMap(4, 2, std::vector<float>(24, 1.0f), Transform(), 1, EnvironmentMap::Mapping::EqualArea);
    ADD_FAILURE();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("latlong"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace dermis
