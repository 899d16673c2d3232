// The lights as a walk inside sees them (lights_from_inside.h): the density of a direction
// integrates to one over the sphere, and the sampler draws by it, for a sphere light and a
// quad (two triangle lights), each within 4 standard errors.
#include "dermis/render/path/lights_from_inside.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "dermis/core/warp.h"
#include "dermis/render/scene_preparation.h"
#include "dermis/scene/parser.h"

namespace dermis {
namespace {

TEST(LightsFromInside, TheDensityIntegratesToOneAndTheSamplerDrawsByIt) {
  const std::string scene = R"(LookAt 0 -4 1  0 0 0  0 0 1
Camera "perspective" "float fov" 30
Film "rgb" "integer xresolution" 8 "integer yresolution" 8
WorldBegin
AttributeBegin
  AreaLightSource "diffuse" "rgb L" [5 5 5]
  Translate 2 -1 3
  Shape "sphere" "float radius" 0.6
AttributeEnd
AttributeBegin
  AreaLightSource "diffuse" "rgb L" [3 3 3] "bool twosided" true
  Shape "bilinearmesh" "point3 P" [-2 2 2  -0.5 2 2  -2 2 3.5  -0.5 2 3.5]
AttributeEnd
Material "subsurface" "rgb sigma_a" [0.1 0.1 0.1] "rgb sigma_s" [2 2 2]
Shape "sphere"
)";
  Diagnostics diag;
  auto sc = build_render_scene(parse_scene_string(scene), diag);
  ASSERT_TRUE(lights_offered_inside(*sc, -1));
  const Vec3 y(0.1f, 0.2f, 0.3f);
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<float> u01(0, 1);
  const int N = 400000;
  double sum = 0, sum2 = 0, support = 0, support2 = 0;
  for (int i = 0; i < N; ++i) {
    const Vec3 w = sample_uniform_sphere({u01(rng), u01(rng)});
    const double x = 4 * kPiD * light_density_from_inside(*sc, y, w), in = x > 0 ? 4 * kPiD : 0.0;
    sum += x, sum2 += x * x, support += in, support2 += in * in;
  }
  const double mean = sum / N, se = std::sqrt((sum2 / N - mean * mean) / N);
  EXPECT_NEAR(mean, 1.0, 4 * se) << "the density's integral";
  const double solid_angle = support / N, solid_angle_se = std::sqrt((support2 / N - solid_angle * solid_angle) / N);
  double inv = 0, inv2 = 0;
  int drawn = 0;
  for (int i = 0; i < N; ++i) {
    Vec3 w;
    float p = 0;
    if (!sample_light_from_inside(*sc, y, u01(rng), u01(rng), w, p)) continue;
    ++drawn;
    inv += 1 / double(p), inv2 += 1 / (double(p) * p);
  }
  EXPECT_EQ(drawn, N);  // no light here that the walks do not sample
  const double mean_inv = inv / N, inv_se = std::sqrt((inv2 / N - mean_inv * mean_inv) / N);
  EXPECT_NEAR(mean_inv, solid_angle, 4 * std::hypot(inv_se, solid_angle_se)) << "the lights' solid angle";
}

}  // namespace
}  // namespace dermis
