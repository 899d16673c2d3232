// The light selection's rule for a uniform sky in a medium (lights/light_selection.h: at
// a point in a medium it gives way to the other lights where they outweigh it, its
// emission then found by the phase function alone) keeps the picture: an index-matched
// scattering sphere under a sky and a brighter spherical light (the sky nearly half of
// the light at the sphere, outweighed there), rendered with the rule
// and without it, agrees region by region within 4 standard errors.
#include <gtest/gtest.h>

#include <string>

#include "dermis/lights/light_selection.h"
#include "dermis/render/scene_preparation.h"
#include "dermis/scene/parser.h"
#include "support/pixel_statistics.h"

namespace dermis {
namespace {

TEST(UniformSkyInMedium, GivingWayKeepsThePicture) {
  const std::string scene = R"(LookAt 0 -4 1.5  0 0 0  0 0 1
Camera "perspective" "float fov" 34
Film "rgb" "integer xresolution" 16 "integer yresolution" 16
Integrator "volpath" "integer maxdepth" 100000
WorldBegin
LightSource "infinite" "rgb L" [0.11 0.12 0.13]
AttributeBegin
  AreaLightSource "diffuse" "rgb L" [60 60 60]
  Translate 2 -2 3
  Shape "sphere" "float radius" 0.5
AttributeEnd
MakeNamedMedium "m" "string type" "homogeneous" "rgb sigma_a" [0.05 0.1 0.2]
  "rgb sigma_s" [2 1.6 1.2] "float g" 0.3
AttributeBegin
  Material "interface"
  MediumInterface "m" ""
  Shape "sphere" "float radius" 0.8
AttributeEnd
)";
  Diagnostics diag;
  auto with_rule = build_render_scene(parse_scene_string(scene), diag);
  auto without = build_render_scene(parse_scene_string(scene), diag);
  without->light_selection = LightSelection(without->lights, without->embree->bounds_radius(), false);
  // The rule acts: in the medium the sky is never chosen with it, and is without it.
  ASSERT_EQ(with_rule->lights.size(), 2u);
  const int sky = with_rule->lights[0].type == Light::Type::Infinite ? 0 : 1;
  EXPECT_EQ(with_rule->light_selection.pmf(sky, {0, 0, 0}, {0, 0, 0}), 0.0f);
  EXPECT_GT(without->light_selection.pmf(sky, {0, 0, 0}, {0, 0, 0}), 0.0f);
  testing::expect_same_region_means(testing::pixel_statistics(*with_rule, 256, 71),
                                    testing::pixel_statistics(*without, 256, 72), 4, 4);
}

}  // namespace
}  // namespace dermis
