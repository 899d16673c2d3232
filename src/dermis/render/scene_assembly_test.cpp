// Scene assembly's choices that rendering tests would not see: hits carry (u, v) exactly
// when the scene has textures to read them (EmbreeScene::set_uv_needed).
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

}  // namespace
}  // namespace dermis
