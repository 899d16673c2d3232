// The lights as a walk inside sees them (lights_from_inside.h): the density of a direction
// integrates to one over the sphere, and the sampler draws by it, for a sphere light and a
// quad (two triangle lights), each within 4 standard errors.
#include "dermis/render/path/lights_from_inside.h"

#include <gtest/gtest.h>

#include "dermis/render/scene_preparation.h"
#include "dermis/scene/parser.h"
#include "support/direction_density.h"

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
  // Every draw succeeds: no light here that the walks do not sample.
  testing::expect_density_and_its_sampler(
      [&](Vec3 w) { return light_density_from_inside(*sc, y, w); },
      [&](float u1, float u2, Vec3& w, float& p) { return sample_light_from_inside(*sc, y, u1, u2, w, p); }, 11);
}

}  // namespace
}  // namespace dermis
