// Scenes reaching beyond the coordinates Embree can trace are refused at their directive
// (they used to abort in Embree's ray.valid() assertion).
#include "dermis/render/scene_extent.h"

#include <gtest/gtest.h>

#include <string>

#include "dermis/render/scene_assembly.h"
#include "dermis/scene/parser.h"

namespace dermis {
namespace {

// The message of the SceneError assembling `world` (after a camera at `eye`) throws, "" if none.
std::string assembly_error(const std::string& world, const std::string& eye = "0 0 5") {
  Diagnostics diag;
  try {
    assemble_scene(parse_scene_string("LookAt " + eye +
                                          "  0 0 0  0 1 0\nCamera \"perspective\"\nFilm \"rgb\" "
                                          "\"integer xresolution\" 4 \"integer yresolution\" 4\nWorldBegin\n" +
                                          world,
                                      "far.pbrt"),
                   diag);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "";
}

TEST(SceneExtent, OrdinaryScenesPass) {
  EXPECT_EQ(assembly_error("Shape \"sphere\" \"float radius\" 1e6\nTranslate 1e16 0 0\nShape \"sphere\"\n"), "");
}

TEST(SceneExtent, FarCameraIsRefusedAtTheCamera) {
  const std::string err = assembly_error("Shape \"sphere\"\n", "1e19 0 5");
  EXPECT_NE(err.find("far.pbrt:2:1: error: the camera lies at (1e+19, 0, 5), beyond"), std::string::npos) << err;
}

TEST(SceneExtent, FarOrHugeShapesAreRefusedAtTheShape) {
  std::string err = assembly_error("Translate 1e18 0 0\nShape \"sphere\"\n");
  EXPECT_NE(err.find("far.pbrt:6:1: error: the sphere lies at"), std::string::npos) << err;
  err = assembly_error("Shape \"sphere\" \"float radius\" 1e30\n");
  EXPECT_NE(err.find("far.pbrt:5:1: error: the sphere"), std::string::npos) << err;
  err = assembly_error("Shape \"trianglemesh\" \"point3 P\" [0 0 0 1 0 0 0 2e17 0]\n");
  EXPECT_NE(err.find("a vertex of the shape lies at (0, 2e+17, 0)"), std::string::npos) << err;
}

TEST(SceneExtent, FarInstancesAndLightsAreRefused) {
  std::string err = assembly_error(
      "ObjectBegin \"o\"\nShape \"sphere\"\nObjectEnd\nTranslate 0 0 -5e17\n"
      "ObjectInstance \"o\"\n");
  EXPECT_NE(err.find("far.pbrt:9:1: error: the instanced object lies at"), std::string::npos) << err;
  err = assembly_error("LightSource \"point\" \"point3 from\" [3e17 0 0]\nShape \"sphere\"\n");
  EXPECT_NE(err.find("far.pbrt:5:1: error: the point light lies at"), std::string::npos) << err;
}

}  // namespace
}  // namespace dermis
