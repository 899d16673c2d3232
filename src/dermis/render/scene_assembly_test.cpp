// Scene assembly's choices that rendering tests would not see: hits carry (u, v) exactly
// when the scene has textures to read them (EmbreeScene::set_uv_needed); a triangle light
// keeps its unit normal when its shape has no shading normals (Light::flat).
#include "dermis/render/scene_assembly.h"

#include <gtest/gtest.h>

#include "dermis/scene/parser.h"

namespace dermis {
namespace {

SurfaceHit hit_sphere_from_below_left(const std::string& world) {
  SceneDesc d = parse_scene_string("WorldBegin\nLightSource \"point\"\n" + world, "uv.pbrt");
  Diagnostics diag;
  auto sc = assemble_scene(d, diag);
  const Vec3 l = normalize(Vec3(-1, -1, -1));
  SurfaceHit h;
  EXPECT_TRUE(sc->embree->intersect(Ray{l * 10.0f, -l}, h));
  return h;
}

TEST(SceneAssembly, ATexturedSceneGetsSphereUvs) {
  const SurfaceHit h = hit_sphere_from_below_left(
      "Texture \"c\" \"spectrum\" \"checkerboard\"\nMaterial \"diffuse\" \"texture reflectance\" \"c\"\n"
      "Shape \"sphere\"\n");
  EXPECT_GT(h.uv.x, 0.5f);  // phi = -3 pi / 4 + 2 pi: u = 0.625
  EXPECT_GT(h.uv.y, 0.1f);  // theta = acos(-1 / sqrt 3): v = 0.196
}

TEST(SceneAssembly, AnUntexturedSceneSkipsSphereUvs) {
  const SurfaceHit h = hit_sphere_from_below_left("Material \"diffuse\"\nShape \"sphere\"\n");
  EXPECT_EQ(h.uv.x, 0.0f);
  EXPECT_EQ(h.uv.y, 0.0f);
}

// Each triangle of an emitting mesh without normals carries the normal triangle_normal
// gives (ReverseOrientation included); with shading normals, it is looked up per sample.
TEST(SceneAssembly, FlatTriangleLightsKeepTheirNormal) {
  const std::string quad = "\"point3 P\" [ 0 0 0  1 0 0  1 1 0  0 1 0 ] \"integer indices\" [ 0 1 2  0 2 3 ]";
  for (const char* orientation : {"", "ReverseOrientation\n"}) {
    SceneDesc d =
        parse_scene_string(std::string("WorldBegin\nAttributeBegin\n") + orientation +
                               "AreaLightSource \"diffuse\"\nShape \"trianglemesh\" " + quad + "\nAttributeEnd\n",
                           "flat.pbrt");
    Diagnostics diag;
    auto sc = assemble_scene(d, diag);
    ASSERT_EQ(sc->lights.size(), 2u);
    for (const Light& l : sc->lights) {
      EXPECT_TRUE(l.flat);
      const Vec3 expected = sc->shapes[l.shape].triangle_normal(l.prim, 0.3f, 0.2f);
      EXPECT_EQ(l.normal, expected);
      EXPECT_FLOAT_EQ(std::abs(l.normal.z), 1.0f);
    }
  }
  SceneDesc d = parse_scene_string("WorldBegin\nAreaLightSource \"diffuse\"\nShape \"trianglemesh\" " + quad +
                                       " \"normal N\" [ 0 0 1  0 0 1  0 0 1  0 0 1 ]\n",
                                   "smooth.pbrt");
  Diagnostics diag;
  auto sc = assemble_scene(d, diag);
  ASSERT_EQ(sc->lights.size(), 2u);
  for (const Light& l : sc->lights) EXPECT_FALSE(l.flat);
}

}  // namespace
}  // namespace dermis
