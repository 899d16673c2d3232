// The lights as a walk inside sees them (lights_from_inside.h): the density of a direction
// integrates to one over the sphere, and the sampler draws by it, for a sphere light and a
// quad (two triangle lights), each within 4 standard errors.
#include "dermis/render/path/lights_from_inside.h"

#include <gtest/gtest.h>

#include "dermis/lights/environment_map.h"
#include "dermis/render/scene_preparation.h"
#include "dermis/scene/parser.h"
#include "dermis/scene/scene_test_util.h"
#include "support/direction_density.h"
#include "support/sky_with_sun.h"

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

// A sky for the test, written in `dir` as NAME.exr (support/sky_with_sun.h); its path.
std::string write_sky(const test::TempDir& dir, const std::string& name, std::optional<Vec3> sun) {
  const std::string path = dir.path() + "/" + name + ".exr";
  testing::write_sky_with_sun(path, sun);
  return path;
}

std::unique_ptr<RenderScene> scene_lit_by(const std::string& lights) {
  Diagnostics diag;
  return build_render_scene(
      parse_scene_string("LookAt 0 -4 1  0 0 0  0 0 1\nCamera \"perspective\"\nWorldBegin\n" + lights +
                         "Material \"subsurface\" \"string name\" \"Skin1\"\nShape \"sphere\"\n"),
      diag);
}

// What the walks aim the plane of refraction at: the finite lights' centre weighted by
// power (environment maps aside); else a map's sun, along its mean direction of arrival;
// nothing for a map that lights evenly.
TEST(LightsFromInside, TheKeyLightIsTheFiniteLightsCentreOrTheSun) {
  test::TempDir dir;
  const Vec3 sun_light_space = normalize(Vec3(0.3f, -0.5f, 0.8f));
  const std::string sky =
      "LightSource \"infinite\" \"string filename\" \"" + write_sky(dir, "sun", sun_light_space) + "\"\n";
  const std::string even =
      "LightSource \"infinite\" \"string filename\" \"" + write_sky(dir, "even", std::nullopt) + "\"\n";
  const std::string two_lights =
      "AttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [3 3 3]\nTranslate 2 0 3\nShape \"sphere\" "
      "\"float radius\" 0.5\nAttributeEnd\nAttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [1 1 1]\n"
      "Translate -2 0 3\nShape \"sphere\" \"float radius\" 0.5\nAttributeEnd\n";
  {
    SCOPED_TRACE("a sun in the map");
    auto sc = scene_lit_by(sky);
    const std::optional<KeyLight> key = key_light(*sc);
    ASSERT_TRUE(key);
    EXPECT_TRUE(key->at_infinity);
    const Vec3 sun = sc->lights.at(0).environment->uv_to_direction(equal_area_sphere_to_square(sun_light_space));
    EXPECT_GT(dot(key->at, sun), std::cos(0.02f)) << key->at.x << " " << key->at.y << " " << key->at.z;
    Vec3 toward;
    ASSERT_TRUE(key_light_direction(key, Vec3(0.3f, 0.1f, 0.2f), toward));
    EXPECT_NEAR(dot(toward, key->at), 1.0f, 1e-6f);  // the same direction from every point
  }
  {
    SCOPED_TRACE("an even map");
    EXPECT_FALSE(key_light(*scene_lit_by(even)));
  }
  {
    SCOPED_TRACE("two area lights of powers 3 and 1, and the sun");
    const std::optional<KeyLight> key = key_light(*scene_lit_by(two_lights + sky));
    ASSERT_TRUE(key);
    EXPECT_FALSE(key->at_infinity);
    EXPECT_NEAR(key->at.x, (3 * 2.0f + 1 * -2.0f) / 4, 1e-4f);
    EXPECT_NEAR(key->at.z, 3.0f, 1e-4f);
    Vec3 toward;
    ASSERT_TRUE(key_light_direction(key, Vec3(0, 0, 0), toward));
    EXPECT_NEAR(dot(toward, normalize(key->at)), 1.0f, 1e-6f);
  }
}

}  // namespace
}  // namespace dermis
