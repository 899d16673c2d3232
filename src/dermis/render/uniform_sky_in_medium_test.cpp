// The light selection's rule for a uniform sky in a medium (lights/light_selection.h: at
// a point in a medium it gives way to the other lights where they outweigh it, its
// emission then found by the phase function alone) keeps the picture: an index-matched
// scattering sphere under the shared sky and lights, rendered with the rule and without
// it, agrees region by region within 4 standard errors.
#include <gtest/gtest.h>

#include <string>

#include "dermis/lights/light_selection.h"
#include "support/lit_sphere_scene.h"

namespace dermis {
namespace {

TEST(UniformSkyInMedium, GivingWayKeepsThePicture) {
  // The shared sky and spherical light, and a brighter point light that outweighs the sky
  // at the sphere (the sky still brings about two fifths of the light there).
  const std::string point = "LightSource \"point\" \"point3 from\" [1 -1 2] \"rgb I\" [80 80 80]\n";
  const std::string scene = testing::lit_sphere_header(16, point) + R"(
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
  int sky = -1;
  for (std::size_t i = 0; i < with_rule->lights.size(); ++i)
    if (with_rule->lights[i].type == Light::Type::Infinite) sky = int(i);
  ASSERT_GE(sky, 0);
  EXPECT_EQ(with_rule->light_selection.pmf(sky, {0, 0, 0}, {0, 0, 0}), 0.0f);
  EXPECT_GT(without->light_selection.pmf(sky, {0, 0, 0}, {0, 0, 0}), 0.0f);
  testing::expect_same_region_means(testing::pixel_statistics(*with_rule, 256, 71),
                                    testing::pixel_statistics(*without, 256, 72), 4, 4);
}

}  // namespace
}  // namespace dermis
