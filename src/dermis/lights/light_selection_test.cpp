// Tests of the light selection: a light is never given probability zero where some of
// it reaches the point's hemisphere (brute force over points on the light), sample()
// chooses with the probabilities pmf() reports (chi-square), the probabilities sum to
// one, a small bright light facing the point gets most of the samples, and in a medium a
// uniform sky gives way to the lights that outweigh it.
#include "dermis/lights/light_selection.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "dermis/core/rng.h"
#include "dermis/core/warp.h"
#include "dermis/lights/environment_map.h"
#include "support/chi_square.h"

namespace dermis {
namespace {

using testing::chi_square;
using testing::kChiSquareAlpha;

Light triangle(Vec3 a, Vec3 b, Vec3 c, float L) {
  Light l;
  l.type = Light::Type::Triangle;
  l.p0 = a, l.p1 = b, l.p2 = c;
  l.area = 0.5f * length(cross(b - a, c - a));
  l.emission = RGB(L);
  return l;
}

Light sky(float L) {
  Light l;
  l.type = Light::Type::Infinite;
  l.emission = RGB(L);
  return l;
}

// A small bright quad, a sky, a sphere light, a point and a spot light.
std::vector<Light> mixed_lights() {
  std::vector<Light> ls;
  ls.push_back(triangle({-0.5f, 3, -0.5f}, {0.5f, 3, -0.5f}, {0.5f, 3, 0.5f}, 40));
  ls.push_back(triangle({-0.5f, 3, -0.5f}, {0.5f, 3, 0.5f}, {-0.5f, 3, 0.5f}, 40));
  ls.push_back(sky(0.1f));
  Light sphere;
  sphere.type = Light::Type::Sphere;
  sphere.center = {3, 0, 0};
  sphere.radius = 0.4f;
  sphere.emission = RGB(5);
  ls.push_back(sphere);
  Light point;
  point.type = Light::Type::Point;
  point.position = {0, -2, 1};
  point.emission = RGB(3);
  ls.push_back(point);
  Light spot;
  spot.type = Light::Type::Spot;
  spot.position = {0, 0, 4};
  spot.direction = {0, 0, -1};
  spot.cos_falloff_start = 0.95f;
  spot.cos_falloff_end = 0.9f;
  spot.emission = RGB(20);
  ls.push_back(spot);
  return ls;
}

TEST(LightSelection, ProbabilitiesSumToOneAndMatchTheChoices) {
  const auto lights = mixed_lights();
  LightSelection sel(lights, 10);
  ASSERT_TRUE(sel.pointwise());
  ASSERT_EQ(sel.groups({0, 0, 1}), 2);  // at a surface, the sky apart from the finite lights
  ASSERT_EQ(sel.groups({0, 0, 0}), 1);  // in a medium, one choice among all
  Rng rng(5, 1);
  for (int trial = 0; trial < 6; ++trial) {
    const Vec3 p{rng.uniform() * 4 - 2, rng.uniform() * 4 - 2, rng.uniform() * 4 - 2};
    const Vec3 n = trial % 3 == 2 ? Vec3(0, 0, 0) : sample_uniform_sphere({rng.uniform(), rng.uniform()});
    double total = 0;
    std::vector<double> expected(lights.size()), observed(lights.size(), 0);
    for (std::size_t i = 0; i < lights.size(); ++i) total += expected[i] = sel.pmf(int(i), p, n);
    const bool split = sel.groups(n) == 2;
    EXPECT_NEAR(total, split ? 2.0 : 1.0, 1e-5);  // one distribution per group
    if (split) {
      EXPECT_FLOAT_EQ(sel.pmf(2, p, n), 1);  // the sky is its group's only light
    }
    const int n_samples = 200000;
    for (int k = 0; k < n_samples; ++k) {
      float pmf;
      const int li = sel.sample(rng.uniform(), p, n, &pmf, nullptr, 0);
      ASSERT_GE(li, 0);
      if (split) {
        ASSERT_NE(li, 2);
      }
      EXPECT_FLOAT_EQ(pmf, sel.pmf(li, p, n));
      ++observed[std::size_t(li)];
    }
    for (double& e : expected) e *= n_samples;
    if (split) {
      expected.erase(expected.begin() + 2);
      observed.erase(observed.begin() + 2);
    }
    auto r = chi_square(observed, expected);
    EXPECT_GT(r.p_value, kChiSquareAlpha) << "trial " << trial << " chi2 " << r.statistic;
    float pmf;
    if (split) {
      EXPECT_EQ(sel.sample(rng.uniform(), p, n, &pmf, nullptr, 1), 2);
    }
  }
}

// The reused number is uniform within each light's share: a 10-bin histogram of it, per
// chosen light, against uniform.
TEST(LightSelection, ReusedNumberIsUniformForEachLight) {
  const auto lights = mixed_lights();
  LightSelection sel(lights, 10);
  const Vec3 p{0.2f, 0.1f, -0.3f}, n = normalize(Vec3(0.3f, 1, 0.2f));
  std::vector<std::vector<double>> hist(lights.size(), std::vector<double>(10, 0));
  Rng rng(12, 4);
  for (int k = 0; k < 400000; ++k) {
    float pmf, u2 = -1;
    const int li = sel.sample(rng.uniform(), p, n, &pmf, &u2);
    ASSERT_GE(u2, 0.0f);
    ASSERT_LT(u2, 1.0f);
    ++hist[std::size_t(li)][std::min(9, int(u2 * 10))];
  }
  for (std::size_t i = 0; i < lights.size(); ++i) {
    double total = 0;
    for (double h : hist[i]) total += h;
    if (total < 1000) continue;
    auto r = chi_square(hist[i], std::vector<double>(10, total / 10));
    EXPECT_GT(r.p_value, kChiSquareAlpha) << "light " << i;
  }
}

// Zero importance only where no point of the light lies above the tangent plane (or, for
// a spot, where p is outside its cone): checked against 4096 points on each area light.
TEST(LightSelection, NoLightThatCanReachThePointIsLeftOut) {
  const auto lights = mixed_lights();
  LightSelection sel(lights, 10);
  Rng rng(9, 2);
  int culled = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    const Vec3 p{rng.uniform() * 8 - 4, rng.uniform() * 8 - 4, rng.uniform() * 8 - 4};
    const Vec3 n = sample_uniform_sphere({rng.uniform(), rng.uniform()});
    for (std::size_t i = 0; i < lights.size(); ++i) {
      if (sel.importance(i, p, n) > 0) continue;
      ++culled;
      const Light& l = lights[i];
      bool reachable = false;
      if (l.type == Light::Type::Triangle || l.type == Light::Type::Sphere) {
        for (int k = 0; k < 4096 && !reachable; ++k) {
          Vec3 q;
          if (l.type == Light::Type::Triangle) {
            Vec2 b = sample_uniform_triangle({rng.uniform(), rng.uniform()});
            q = l.p0 * (1 - b.x - b.y) + l.p1 * b.x + l.p2 * b.y;
          } else {
            q = l.center + sample_uniform_sphere({rng.uniform(), rng.uniform()}) * l.radius;
          }
          reachable = dot(q - p, n) > 0;
        }
      } else if (l.type == Light::Type::Point || l.type == Light::Type::Spot) {
        const Vec3 d = normalize(l.position - p);
        reachable = dot(d, n) > 0 && (l.type == Light::Type::Point || dot(-d, l.direction) > l.cos_falloff_end);
      } else {
        reachable = true;  // the sky is never culled
      }
      EXPECT_FALSE(reachable) << "light " << i << " culled at p (" << p.x << ", " << p.y << ", " << p.z << ")";
    }
  }
  EXPECT_GT(culled, 1000);  // the test saw culling happen
}

// Above a small bright quad-facing point, the quad outweighs a dim sky (the case the
// point-wise selection is for); below the quad's plane facing away, the sky takes all.
TEST(LightSelection, ABrightKeyLightGetsTheSamplesWhereItShines) {
  std::vector<Light> lights = {triangle({-0.5f, 3, -0.5f}, {0.5f, 3, -0.5f}, {0.5f, 3, 0.5f}, 40),
                               triangle({-0.5f, 3, -0.5f}, {0.5f, 3, 0.5f}, {-0.5f, 3, 0.5f}, 40), sky(0.1f)};
  LightSelection sel(lights, 10);
  const Vec3 p{0, 0, 0};
  EXPECT_GT(sel.pmf(0, p, {0, 1, 0}) + sel.pmf(1, p, {0, 1, 0}), 0.8f);
  EXPECT_FLOAT_EQ(sel.pmf(2, p, {0, -1, 0}), 1.0f);
}

// At a point in a medium (normal zero) a uniform sky gives way to the lights that outweigh
// it there: its light samples would repeat the phase function's. Where no other light
// reaches the point, where the sky outweighs them, at surfaces, with the rule off, and for
// a sky alone, it keeps its share.
TEST(LightSelection, AUniformSkyGivesWayInAMediumToLightsThatOutweighIt) {
  const std::vector<Light> lights = {triangle({-0.5f, 3, -0.5f}, {0.5f, 3, -0.5f}, {0.5f, 3, 0.5f}, 40),
                                     triangle({-0.5f, 3, -0.5f}, {0.5f, 3, 0.5f}, {-0.5f, 3, 0.5f}, 40), sky(0.1f)};
  const LightSelection sel(lights, 10);
  const Vec3 p{0, 0, 0}, in_medium{0, 0, 0};
  EXPECT_EQ(sel.pmf(2, p, in_medium), 0.0f);
  EXPECT_FLOAT_EQ(sel.pmf(0, p, in_medium) + sel.pmf(1, p, in_medium), 1.0f);
  for (int k = 0; k < 64; ++k) {
    float pmf = 0;
    const int chosen = sel.sample((float(k) + 0.5f) / 64, p, in_medium, &pmf);
    EXPECT_NE(chosen, 2);
    EXPECT_FLOAT_EQ(pmf, sel.pmf(chosen, p, in_medium));
  }
  EXPECT_FLOAT_EQ(sel.pmf(2, p, {0, -1, 0}), 1.0f);                             // a surface: the sky's own group
  EXPECT_GT(LightSelection(lights, 10, false).pmf(2, p, in_medium), 0.0f);      // the rule off
  EXPECT_FLOAT_EQ(LightSelection({sky(0.1f)}, 10).pmf(0, p, in_medium), 1.0f);  // the sky alone
  // A sky bright enough to outweigh the quad keeps its share (its importance there, 4 pi L,
  // against the quad's L A cos / d^2).
  const std::vector<Light> bright = {lights[0], lights[1], sky(40)};
  const LightSelection bright_sky(bright, 10);
  EXPECT_GT(bright_sky.importance(2, p, in_medium),
            bright_sky.importance(0, p, in_medium) + bright_sky.importance(1, p, in_medium));
  EXPECT_GT(bright_sky.pmf(2, p, in_medium), 0.5f);

  // A spot light aimed away from the point cannot reach it: the sky keeps everything there.
  Light spot;
  spot.type = Light::Type::Spot;
  spot.position = {0, 0, 4};
  spot.direction = {0, 0, 1};
  spot.cos_falloff_start = 0.95f;
  spot.cos_falloff_end = 0.9f;
  spot.emission = RGB(20);
  const LightSelection away({spot, sky(0.1f)}, 10);
  EXPECT_FLOAT_EQ(away.pmf(1, p, in_medium), 1.0f);
  float pmf = 0;
  EXPECT_EQ(away.sample(0.5f, p, in_medium, &pmf), 1);
}

// At a surface, a uniform sky is outweighed where the finite lights' importances (the sum
// sample() reports for group 0) exceed its own, pi L: facing a bright quad, not facing away
// from it (importance zero), not when the sky is bright, not for a sky with an image, not
// with the rule off, and never with lights at infinity alone. Where it is outweighed it
// gives way at a point that asks for it (SkyRule::Outweighed): its group chooses no light and its
// probability is zero; at other surface points it keeps its group.
TEST(LightSelection, AUniformSkyGivesWayAtASurfaceWhereTheFiniteLightsOutweighIt) {
  const std::vector<Light> lights = {triangle({-0.5f, 3, -0.5f}, {0.5f, 3, -0.5f}, {0.5f, 3, 0.5f}, 40),
                                     triangle({-0.5f, 3, -0.5f}, {0.5f, 3, 0.5f}, {-0.5f, 3, 0.5f}, 40), sky(0.1f)};
  const LightSelection sel(lights, 10);
  const Vec3 p{0, 0, 0};
  auto finite_importance = [&](const LightSelection& s, Vec3 n) {
    float pmf = 0, sum = -1;
    s.sample(0.5f, p, n, &pmf, nullptr, 0, &sum);
    return sum;
  };
  const float facing = finite_importance(sel, {0, 1, 0});
  EXPECT_FLOAT_EQ(facing, sel.importance(0, p, {0, 1, 0}) + sel.importance(1, p, {0, 1, 0}));
  EXPECT_GT(facing, sel.importance(2, p, {0, 1, 0}));
  EXPECT_TRUE(sel.uniform_sky_outweighed(facing));
  EXPECT_FALSE(sel.uniform_sky_outweighed(finite_importance(sel, {0, -1, 0})));  // the quad behind
  EXPECT_EQ(finite_importance(sel, {0, -1, 0}), 0.0f);
  float pmf = 1;
  EXPECT_EQ(sel.sample(0.5f, p, {0, 1, 0}, &pmf, nullptr, 1, nullptr, SkyRule::Outweighed),
            -1);  // facing: the sky gives way
  EXPECT_EQ(pmf, 0.0f);
  EXPECT_EQ(sel.pmf(2, p, {0, 1, 0}, SkyRule::Outweighed), 0.0f);
  EXPECT_EQ(sel.sample(0.5f, p, {0, 1, 0}, &pmf, nullptr, 1), 2);  // not asked for: it keeps its group
  EXPECT_FLOAT_EQ(sel.pmf(2, p, {0, 1, 0}), 1.0f);
  EXPECT_EQ(sel.sample(0.5f, p, {0, -1, 0}, &pmf, nullptr, 1, nullptr, SkyRule::Outweighed), 2);  // the quad behind
  EXPECT_FLOAT_EQ(pmf, 1.0f);
  EXPECT_FLOAT_EQ(sel.pmf(2, p, {0, -1, 0}, SkyRule::Outweighed), 1.0f);
  const LightSelection off(lights, 10, false);
  EXPECT_FALSE(off.uniform_sky_outweighed(finite_importance(off, {0, 1, 0})));
  EXPECT_FLOAT_EQ(off.pmf(2, p, {0, 1, 0}, SkyRule::Outweighed), 1.0f);

  const LightSelection bright_sky({lights[0], lights[1], sky(400)}, 10);
  EXPECT_FALSE(bright_sky.uniform_sky_outweighed(finite_importance(bright_sky, {0, 1, 0})));
  EXPECT_FLOAT_EQ(bright_sky.pmf(2, p, {0, 1, 0}, SkyRule::Outweighed), 1.0f);

  Light map = sky(0.1f);
  map.environment = std::make_shared<const EnvironmentMap>(2, 1, std::vector<float>(6, 0.1f), Transform(), 1.0f,
                                                           EnvironmentMap::Mapping::LatLong);
  const LightSelection with_map({lights[0], lights[1], map}, 10);
  EXPECT_FALSE(with_map.uniform_sky_outweighed(finite_importance(with_map, {0, 1, 0})));
  EXPECT_FLOAT_EQ(with_map.pmf(2, p, {0, 1, 0}, SkyRule::Outweighed), 1.0f);

  const LightSelection sky_alone({sky(0.1f)}, 10);
  EXPECT_FALSE(sky_alone.uniform_sky_outweighed(1e30f));
}

// SkyRule::GivesWay: at a surface point, uniform skies are never chosen and have
// probability zero, whatever the other lights (none, a dim quad, a sky with an image in
// their group); the other lights keep their shares. In a medium the rule is the usual one.
// gives_way_leaves_none says when the rule leaves no light at all: uniform skies alone (or
// none), not with a finite light or a sky with an image.
TEST(LightSelection, AUniformSkyAlwaysGivesWayWhereTheCallerAsks) {
  const Vec3 p{0, 0, 0}, up{0, 1, 0};
  float pmf = 1;
  const LightSelection sky_alone({sky(0.1f)}, 10);
  EXPECT_TRUE(sky_alone.has_uniform_sky());
  EXPECT_TRUE(sky_alone.gives_way_leaves_none());
  EXPECT_TRUE(LightSelection({}, 10).gives_way_leaves_none());
  const LightSelection two_skies({sky(0.1f), sky(2)}, 10);
  EXPECT_TRUE(two_skies.gives_way_leaves_none());
  for (float u : {0.0f, 0.5f, 0.99f})
    EXPECT_EQ(two_skies.sample(u, p, up, &pmf, nullptr, 0, nullptr, SkyRule::GivesWay), -1);
  EXPECT_EQ(sky_alone.sample(0.5f, p, up, &pmf, nullptr, 0, nullptr, SkyRule::GivesWay), -1);
  EXPECT_EQ(pmf, 0.0f);
  EXPECT_EQ(sky_alone.pmf(0, p, up, SkyRule::GivesWay), 0.0f);
  EXPECT_EQ(sky_alone.sample(0.5f, p, up, &pmf, nullptr, 0, nullptr, SkyRule::Outweighed), 0);  // alone: kept
  EXPECT_FLOAT_EQ(sky_alone.pmf(0, p, up, SkyRule::Outweighed), 1.0f);
  EXPECT_FLOAT_EQ(sky_alone.pmf(0, p, Vec3(0, 0, 0), SkyRule::GivesWay), 1.0f);  // in a medium

  // A dim quad (the sky outweighs it) and the sky: two groups; the sky's chooses none.
  const std::vector<Light> quad_and_sky = {triangle({-0.5f, 3, -0.5f}, {0.5f, 3, -0.5f}, {0.5f, 3, 0.5f}, 0.01f),
                                           sky(10)};
  const LightSelection both(quad_and_sky, 10);
  EXPECT_FALSE(both.gives_way_leaves_none());
  ASSERT_EQ(both.groups(up), 2);
  EXPECT_EQ(both.sample(0.5f, p, up, &pmf, nullptr, 1, nullptr, SkyRule::GivesWay), -1);
  EXPECT_EQ(both.pmf(1, p, up, SkyRule::GivesWay), 0.0f);
  EXPECT_FLOAT_EQ(both.pmf(1, p, up, SkyRule::Outweighed), 1.0f);  // not outweighed: sampled
  EXPECT_EQ(both.sample(0.5f, p, up, &pmf, nullptr, 0, nullptr, SkyRule::GivesWay), 0);
  EXPECT_FLOAT_EQ(pmf, 1.0f);

  // A sky with an image keeps its group; the uniform one beside it gives way.
  Light map = sky(0.1f);
  map.environment = std::make_shared<const EnvironmentMap>(2, 1, std::vector<float>(6, 0.1f), Transform(), 1.0f,
                                                           EnvironmentMap::Mapping::LatLong);
  const LightSelection skies({map, sky(0.1f)}, 10);
  EXPECT_FLOAT_EQ(skies.pmf(0, p, up, SkyRule::GivesWay), 1.0f);
  EXPECT_EQ(skies.pmf(1, p, up, SkyRule::GivesWay), 0.0f);
  EXPECT_EQ(skies.sample(0.99f, p, up, &pmf, nullptr, 0, nullptr, SkyRule::GivesWay), 0);

  EXPECT_FALSE(skies.gives_way_leaves_none());
  const LightSelection map_alone({map}, 10);
  EXPECT_FALSE(map_alone.has_uniform_sky());
  EXPECT_FALSE(map_alone.gives_way_leaves_none());
}

TEST(LightSelection, ManyLightsUseThePowerDistribution) {
  std::vector<Light> lights;
  for (int i = 0; i < int(kPointwiseLightLimit) + 1; ++i)
    lights.push_back(triangle({float(i), 0, 0}, {float(i) + 1, 0, 0}, {float(i), 1, 0}, 1.0f + float(i)));
  LightSelection sel(lights, 10);
  EXPECT_FALSE(sel.pointwise());
  // In proportion to power (area x radiance; all areas equal).
  double sum = 0;
  for (int i = 0; i < int(lights.size()); ++i) sum += 1.0 + i;
  for (int i = 0; i < int(lights.size()); ++i) EXPECT_NEAR(sel.pmf(i, {0, 0, 0}, {0, 0, 1}), (1.0 + i) / sum, 1e-5);
}

// Lights near the range of floats: the probabilities stay finite and exact (a sky of
// 3e38 made pi L infinite and every probability NaN; a distant light's power pi r^2 L in a
// scene of radius 1e17 stopped the power table with "value 0 of the function is inf").
TEST(LightSelection, LightsNearTheRangeOfFloatsKeepExactProbabilities) {
  Light sun;
  sun.type = Light::Type::Distant;
  sun.direction = {0, 0, 1};
  sun.emission = RGB(3e38f);
  {
    // Pointwise, one group (both at infinity): the sky's importance pi L, the sun's L cos.
    LightSelection sel({sky(3e38f), sun}, 1e17f);
    ASSERT_TRUE(sel.pointwise());
    const Vec3 n = normalize(Vec3(0, 1, 1));
    const double c = dot(n, sun.direction), pi = 3.14159265358979;
    EXPECT_NEAR(sel.pmf(0, {0, 0, 0}, n), pi / (pi + c), 1e-6);
    EXPECT_NEAR(sel.pmf(1, {0, 0, 0}, n), c / (pi + c), 1e-6);
  }
  {
    // Two point lights of I = 2e37 (power 2.5e38, in range) at 0.1 and 0.2: I / d^2 is
    // beyond float, the ratio 4 : 1 is not.
    Light a, b;
    a.type = b.type = Light::Type::Point;
    a.emission = b.emission = RGB(2e37f);
    a.position = {0, 0, 0.1f};
    b.position = {0, 0, 0.2f};
    LightSelection sel({a, b}, 1);
    EXPECT_NEAR(sel.pmf(0, {0, 0, 0}, {0, 0, 1}), 0.8, 1e-6);
    EXPECT_NEAR(sel.pmf(1, {0, 0, 0}, {0, 0, 1}), 0.2, 1e-6);
  }
  {
    // The power table (more lights than the pointwise limit): the sun's group gets one half.
    std::vector<Light> lights;
    for (int i = 0; i < int(kPointwiseLightLimit); ++i)
      lights.push_back(triangle({float(i), 0, 0}, {float(i) + 1, 0, 0}, {float(i), 1, 0}, 1));
    lights.push_back(sun);
    LightSelection sel(lights, 1e17f);
    ASSERT_FALSE(sel.pointwise());
    EXPECT_NEAR(sel.pmf(int(kPointwiseLightLimit), {0, 0, 0}, {0, 0, 1}), 0.5, 1e-6);
    EXPECT_NEAR(sel.pmf(0, {0, 0, 0}, {0, 0, 1}), 0.5 / double(kPointwiseLightLimit), 1e-6);
  }
}

TEST(LightSelection, NoLightsNoChoice) {
  LightSelection sel(std::vector<Light>{}, 1);
  float pmf = 1;
  EXPECT_EQ(sel.sample(0.5f, {0, 0, 0}, {0, 0, 1}, &pmf), -1);
  EXPECT_EQ(pmf, 0.0f);
}

// may_meet_finite_emitter (the integrator's test before it traces a reflection that could
// only matter if it met a light) is conservative: never false for a ray that meets an
// area light (rays from random points toward random points on the quad and the sphere
// light), false for rays that pass beside every area light, and true whenever the
// bounds are not kept.
TEST(LightSelection, MayMeetFiniteEmitterIsNeverFalseForARayThatMeetsOne) {
  const std::vector<Light> lights = mixed_lights();
  const LightSelection sel(lights, 10);
  ASSERT_TRUE(sel.pointwise());
  Rng rng(17, 0);
  for (int k = 0; k < 20000; ++k) {
    const Vec3 o(4 * rng.uniform() - 2, 4 * rng.uniform() - 2, 4 * rng.uniform() - 2);
    Vec3 target;
    if (k % 2 == 0) {
      const Light& t = lights[k % 4 == 0 ? 0 : 1];
      const Vec2 b = sample_uniform_triangle({rng.uniform(), rng.uniform()});
      target = t.p0 * b.x + t.p1 * b.y + t.p2 * (1 - b.x - b.y);
    } else {
      target = lights[3].center + lights[3].radius * sample_uniform_sphere({rng.uniform(), rng.uniform()});
    }
    const Vec3 d = normalize(target - o);
    ASSERT_TRUE(sel.may_meet_finite_emitter(o, d)) << k;
  }
  // Beside every area light: point and spot lights are not met by rays.
  EXPECT_FALSE(sel.may_meet_finite_emitter({0, 0, 0}, {0, -1, 0}));
  EXPECT_FALSE(sel.may_meet_finite_emitter({0, 0, 0}, normalize(Vec3(0, -2, 1))));  // toward the point light
  EXPECT_FALSE(sel.may_meet_finite_emitter({0, 0, 0}, {0, 0, 1}));                  // toward the spot light
  EXPECT_FALSE(sel.may_meet_finite_emitter({0, 0, 0}, {-1, 0, 0}));                 // away from the sphere light
  EXPECT_TRUE(sel.may_meet_finite_emitter({3, 0.1f, 0}, {0, -1, 0}));               // from inside its bounds
  // Without the bounds (more lights than kPointwiseLightLimit): always true.
  std::vector<Light> many;
  for (std::size_t i = 0; i <= kPointwiseLightLimit; ++i)
    many.push_back(triangle({float(i), 3, 0}, {float(i) + 0.5f, 3, 0}, {float(i), 3, 0.5f}, 1));
  EXPECT_TRUE(LightSelection(many, 10).may_meet_finite_emitter({0, 0, 0}, {0, -1, 0}));
}

}  // namespace
}  // namespace dermis
