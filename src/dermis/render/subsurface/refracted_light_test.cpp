// Light sampled through a smooth boundary from inside (refracted_light.h): the refraction
// through the plane and its solid-angle ratio, and the walk with it against the walk
// without it (the same mean).
#include "dermis/render/subsurface/refracted_light.h"

#include <gtest/gtest.h>

#include <cmath>

#include "dermis/core/frame.h"
#include "dermis/core/warp.h"
#include "dermis/render/scene_preparation.h"
#include "dermis/scene/parser.h"
#include "dermis/scene/scene_test_util.h"
#include "support/direction_density.h"
#include "support/lit_sphere_scene.h"
#include "support/pixel_statistics.h"
#include "support/sky_with_sun.h"

namespace dermis {
namespace {

TEST(RefractedLight, RefractionThroughThePlaneInvertsAndObeysSnell) {
  const Vec3 n = normalize(Vec3(0.2f, -0.3f, 1));
  const float eta = 1.4f;
  for (Vec3 w : {Vec3(0, 0, 1), Vec3(0.5f, 0.1f, 0.8f), Vec3(-0.9f, 0.2f, 0.3f)}) {
    w = normalize(w);
    if (dot(w, n) <= 0) continue;
    float j_in = 0, j_out = 0;
    const auto v = refracted_in(w, n, eta, &j_in);
    ASSERT_TRUE(v);
    const auto back = refracted_out(*v, n, eta, &j_out);
    ASSERT_TRUE(back);
    EXPECT_NEAR(length(*back - w), 0, 1e-5f);
    EXPECT_NEAR(j_in, j_out, 1e-4f * j_in);
    // Snell: sin(w) = eta sin(v).
    const float sin_w = std::sqrt(std::max(0.0f, 1 - dot(w, n) * dot(w, n)));
    const float sin_v = std::sqrt(std::max(0.0f, 1 - dot(*v, n) * dot(*v, n)));
    EXPECT_NEAR(sin_w, eta * sin_v, 1e-5f);
  }
  // Beyond the critical angle no flight leaves.
  EXPECT_FALSE(refracted_out(normalize(Vec3(1, 0, 0.3f)), Vec3(0, 0, 1), 1.4f));
}

// The Jacobian dw/dv: the solid angle of a small cone of inside directions, mapped out,
// over its own (a cone of half-angle 1e-3 about v, measured by the spread of its image).
TEST(RefractedLight, TheJacobianIsTheRatioOfSolidAngles) {
  const Vec3 n(0, 0, 1);
  const float eta = 1.33f;
  for (float theta : {0.1f, 0.4f, 0.6f}) {
    const Vec3 v(std::sin(theta), 0, std::cos(theta));
    float j = 0;
    const auto w = refracted_out(v, n, eta, &j);
    ASSERT_TRUE(w);
    const float h = 1e-3f;
    const Vec3 vx = normalize(v + Vec3(std::cos(theta), 0, -std::sin(theta)) * h), vy = normalize(v + Vec3(0, h, 0));
    const Vec3 wx = *refracted_out(vx, n, eta), wy = *refracted_out(vy, n, eta);
    const float area_v = length(cross(vx - v, vy - v)), area_w = length(cross(wx - *w, wy - *w));
    EXPECT_NEAR(area_w / area_v, j, 2e-2f * j) << theta;
  }
}

// The technique's density over the directions inside: a light of uniform density over a
// cone of directions (half-angle 25 degrees, tilted 30 degrees from the plane's normal, all
// above the plane). The density integrates to one (the mean of 4 pi p(v) over uniform
// directions), and the sampler draws by it (the mean of 1 / p(v) over its samples is the
// solid angle where p > 0, measured by uniform directions): each within 4 standard errors.
TEST(RefractedLight, TheDensityIntegratesToOneAndTheSamplerDrawsByIt) {
  const Vec3 n(0, 0, 1), axis = normalize(Vec3(std::sin(0.52f), 0, std::cos(0.52f)));
  const float cos_max = std::cos(0.436f), eta = 1.33f;
  const Frame frame(axis);
  auto sample = [&](Vec3, float u1, float u2, Vec3& w, float& density) {
    w = frame.to_world(sample_uniform_cone({u1, u2}, cos_max));
    density = uniform_cone_pdf(cos_max);
    return true;
  };
  auto light_density = [&](Vec3, Vec3 w) { return dot(w, axis) >= cos_max ? uniform_cone_pdf(cos_max) : 0.0f; };
  auto emission = [](Vec3, Vec3, Vec3) { return RGB(0); };
  auto key = [](Vec3, Vec3&) { return false; };
  const LightsFromInside lights{sample, light_density, emission, key};
  const RefractedLight technique(lights, eta);
  const Vec3 y(0, 0, -1);
  testing::expect_density_and_its_sampler(
      [&](Vec3 v) { return technique.density(y, n, v); },
      [&](float u1, float u2, Vec3& v, float& p) { return technique.sample(y, n, u1, u2, v, p); }, 7);
}

// The scene rendered with light sampled through the boundary and without (512 samples per
// pixel, seeds seed and seed + 1): the same means over the whole 16 x 16 image, where the
// comparison must be able to see a bias of `detectable_bias`, and in 16 regions.
void expect_the_walk_keeps_its_mean(const std::string& scene, uint64_t seed, double detectable_bias) {
  Diagnostics diag;
  auto with = build_render_scene(parse_scene_string(scene), diag);
  auto without = build_render_scene(parse_scene_string(scene), diag);
  without->switches.refracted_light = false;
  const auto a = testing::pixel_statistics(*with, 512, seed), b = testing::pixel_statistics(*without, 512, seed + 1);
  {
    SCOPED_TRACE("the whole image");
    testing::expect_same_region_means(a, b, 16, 16, detectable_bias);
  }
  SCOPED_TRACE("16 regions");
  testing::expect_same_region_means(a, b, 4, 4);
}

// The walk behind a smooth dielectric with light sampled through it and without: the same
// picture (the image's mean, then 16 regions, within 4 standard errors), under a sky and a
// small light, in a medium that absorbs (a scattering event's albedo left out of the light
// sample read 1 to 3 % high: the comparison sees a 2 % bias, which the helper asserts).
TEST(RefractedLight, TheWalkKeepsItsMean) {
  const std::string scene =
      testing::lit_sphere_header(16) +
      "Material \"subsurface\" \"rgb sigma_a\" [0.3 0.6 1.0] \"rgb sigma_s\" [2 3 4] \"float eta\" 1.33 "
      "\"float g\" 0.3 \"string boundary\" \"dielectric\"\nShape \"sphere\"\n";
  expect_the_walk_keeps_its_mean(scene, 51, 0.02);
}

// The same under an environment map alone, a sky with a sun (the walks aim the plane of
// refraction at the sun's direction: lights_from_inside.h, KeyLight, and refine it by one
// step toward where the refracted flight leaves: walk_method.cpp), on a sphere. The sun is
// broad (30 degrees) so that the walks without the technique find it often enough for the
// comparison to see a 3 % bias (the emission weighed against a plane other than the one its
// light sample used reads 5 to 12 % high here).
TEST(RefractedLight, TheWalkKeepsItsMeanUnderASun) {
  test::TempDir dir;
  const std::string sky = dir.path() + "/sky.exr";
  testing::write_sky_with_sun(sky, normalize(Vec3(0.6f, 0.3f, 0.75f)), 0.5f, 8);
  const std::string scene = R"(LookAt 0 -4 1.5  0 0 0  0 0 1
Camera "perspective" "float fov" 34
Film "rgb" "integer xresolution" 16 "integer yresolution" 16
Integrator "volpath" "integer maxdepth" 100000
WorldBegin
LightSource "infinite" "string filename" ")" +
                            sky + R"("
Material "subsurface" "rgb sigma_a" [0.2 0.5 1.0] "rgb sigma_s" [3 4 5] "float eta" 1.4
Shape "sphere"
)";
  expect_the_walk_keeps_its_mean(scene, 71, 0.03);
}

// Under a small light alone, behind the sphere's side (no highlight in view), in a dense
// medium (mean free paths a few percent of the radius: the boundary near a walk is nearly
// its plane), the walks that leave find the light by chance, the light samples nearly
// always: the pixels' variance falls at least four-fold (the same seeds; their standard
// errors).
TEST(RefractedLight, ASmallLightIsFoundWithLessVariance) {
  const std::string scene = R"(LookAt 0 -4 1.5  0 0 0  0 0 1
Camera "perspective" "float fov" 34
Film "rgb" "integer xresolution" 16 "integer yresolution" 16
Integrator "volpath" "integer maxdepth" 100000
WorldBegin
AttributeBegin
  AreaLightSource "diffuse" "rgb L" [60 60 60]
  Translate 2.5 1 2
  Shape "sphere" "float radius" 0.15
AttributeEnd
Material "subsurface" "rgb sigma_a" [0.5 1.5 3] "rgb sigma_s" [20 30 40] "float eta" 1.33
  "string boundary" "dielectric"
Shape "sphere"
)";
  Diagnostics diag;
  auto with = build_render_scene(parse_scene_string(scene), diag);
  auto without = build_render_scene(parse_scene_string(scene), diag);
  without->switches.refracted_light = false;
  const auto a = testing::pixel_statistics(*with, 64, 61), b = testing::pixel_statistics(*without, 64, 61);
  double var_a = 0, var_b = 0;
  for (std::size_t p = 0; p < a.mean.size(); ++p)
    for (int c = 0; c < 3; ++c) {
      var_a += double(a.stderr_[p][c]) * a.stderr_[p][c];
      var_b += double(b.stderr_[p][c]) * b.stderr_[p][c];
    }
  EXPECT_LT(var_a, 0.25 * var_b) << "with " << var_a << ", without " << var_b;
}

}  // namespace
}  // namespace dermis
