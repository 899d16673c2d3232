// The camera's first smooth reflection, split off at a subsurface entry and at glass, is
// rouletted where it cannot see a bright emitter (integrator.cpp, reflection_survival,
// Russian roulette on the branch's throughput F): under a sky at the reflected path's first
// vertex, so that the sky its first ray meets counts in full; without a sky before the ray
// is traced. The picture is that of following it always, region by region within 4
// standard errors, with a floor that the lower half's reflection meets (the roulette at
// work). Under a bright sky the reflection is a tenth of the sphere's light and more at its
// rim. Checked against a broken weight (the surviving reflection not divided by its
// probability, at the first vertex or before the ray): each scene fails by more than 4
// sigma in some region.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "support/lit_sphere_scene.h"

namespace dermis {
namespace {

const char* kCoefficients = R"("rgb sigma_a" [0.05 0.15 0.3] "rgb sigma_s" [2 3 4] "float g" 0.3)";

std::vector<std::string> objects() {
  return {
      std::string("Material \"subsurface\" ") + kCoefficients + " \"float eta\" 1.4 \"string method\" \"randomwalk\"\n",
      std::string("Material \"subsurface\" ") + kCoefficients +
          " \"float eta\" 1.4 \"string method\" \"disk\" \"string profile\" \"burley\"\n",
      std::string("Material \"dielectric\" \"float eta\" 1.5\n")};
}

// A grey floor under the unit sphere, seen in its lower half's reflection.
const char* kFloor =
    "AttributeBegin\nMaterial \"diffuse\" \"rgb reflectance\" [0.5 0.5 0.5]\n"
    "Shape \"trianglemesh\" \"point3 P\" [-20 -20 -1 20 -20 -1 20 20 -1 -20 20 -1] \"integer indices\" [0 1 2 0 2 3]\n"
    "AttributeEnd\n";

void expect_picture_of_following_always(const std::string& scene, uint64_t seed) {
  Diagnostics diag;
  auto sc = build_render_scene(parse_scene_string(scene), diag);
  const auto a = testing::pixel_statistics(*sc, 256, seed);
  sc->switches.reflection_roulette = false;  // followed always
  const auto b = testing::pixel_statistics(*sc, 256, seed + 1);
  testing::expect_same_region_means(a, b, 4, 4);
  testing::expect_same_region_means(a, b, 16, 16);  // the whole image as one region
}

TEST(ReflectionRoulette, KeepsThePictureAtSubsurfaceEntriesAndGlass) {
  const std::string header = testing::lit_sphere_header(16, "LightSource \"infinite\" \"rgb L\" [3 3 3]\n");
  for (const std::string& object : objects()) {
    SCOPED_TRACE(object);
    expect_picture_of_following_always(header + kFloor + object + "Shape \"sphere\"\n", 81);
  }
}

// Without a sky the roulette is decided before the reflected ray is traced.
TEST(ReflectionRoulette, KeepsThePictureWithoutASky) {
  std::string header = testing::lit_sphere_header(16);
  const std::string sky = "LightSource \"infinite\" \"rgb L\" [0.6 0.7 0.8]\n";
  ASSERT_NE(header.find(sky), std::string::npos);
  header.erase(header.find(sky), sky.size());
  for (const std::string& object : objects()) {
    SCOPED_TRACE(object);
    expect_picture_of_following_always(header + kFloor + object + "Shape \"sphere\"\n", 83);
  }
}

// Under a sky, a convex object's reflection meets nothing but the sky: it is never
// rouletted, sample for sample the image of following it always (before, rouletted ahead
// of the ray, it was met by about one sample in 1/F).
TEST(ReflectionRoulette, ASkySeenInTheReflectionCountsInEverySample) {
  const std::string header = testing::lit_sphere_header(8);
  for (const std::string& object : objects()) {
    SCOPED_TRACE(object);
    Diagnostics diag;
    auto sc = build_render_scene(parse_scene_string(header + object + "Shape \"sphere\"\n"), diag);
    const auto a = testing::pixel_statistics(*sc, 16, 85);
    sc->switches.reflection_roulette = false;  // followed always
    const auto b = testing::pixel_statistics(*sc, 16, 85);
    for (std::size_t p = 0; p < a.mean.size(); ++p)
      for (int c = 0; c < 3; ++c) ASSERT_EQ(a.mean[p][c], b.mean[p][c]) << "pixel " << p << " channel " << c;
  }
}

}  // namespace
}  // namespace dermis
