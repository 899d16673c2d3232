// The default for a subsurface material given by its coefficients (sigma_a + sigma_s, or a
// named measured medium) renders the medium it describes: the random walk with the
// `dielectric` boundary, against the `volumetric` method (the medium inside a smooth
// dielectric, rendered by the volumetric path tracer), in the whole image's mean and in
// 16 regions, each within 4 standard errors of the difference.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "dermis/render/scene_preparation.h"
#include "dermis/scene/parser.h"
#include "support/lit_sphere_scene.h"
#include "support/pixel_statistics.h"

namespace dermis {
namespace {

const std::string kHeader = testing::lit_sphere_header(16);
const char* kCoefficients = R"("rgb sigma_a" [0.05 0.15 0.3] "rgb sigma_s" [2 3 4] "float eta" 1.33)";
// A slab 0.4 thick (0.8 to 1.7 mean free paths with the coefficients above), 2 x 2 wide.
const char* kSlab = R"(Shape "trianglemesh" "point3 P" [-1 -0.2 -1  1 -0.2 -1  1 0.2 -1  -1 0.2 -1
                                  -1 -0.2 1  1 -0.2 1  1 0.2 1  -1 0.2 1]
  "integer indices" [0 2 1  0 3 2   4 5 6  4 6 7   0 1 5  0 5 4   1 2 6  1 6 5   2 3 7  2 7 6   3 0 4  3 4 7]
)";

testing::PixelStatistics render(const std::string& scene, int spp, uint64_t seed) {
  Diagnostics diag;
  auto sc = build_render_scene(parse_scene_string(scene), diag);
  return testing::pixel_statistics(*sc, spp, seed);
}

// The material as written (no method, no boundary) against the same material with
// "string method" "volumetric": the image's mean, then its 4 x 4 regions of 4 x 4 pixels.
void expect_default_is_the_medium(const std::string& material, const std::string& shape, int spp,
                                  double detectable_bias) {
  const auto by_default = render(kHeader + material + "\n" + shape, spp, 41);
  const auto exact = render(kHeader + material + " \"string method\" \"volumetric\"\n" + shape, spp, 42);
  {
    SCOPED_TRACE("the whole image");
    testing::expect_same_region_means(by_default, exact, 16, 16);
  }
  SCOPED_TRACE("16 regions");
  testing::expect_same_region_means(by_default, exact, 4, 4, detectable_bias);
}

TEST(SubsurfaceDefaultBoundary, ACoefficientGivenSphereRendersTheMediumItDescribes) {
  // 5 %: well under the +9 to +28 % the diffuse boundary read on such a sphere (issue 69).
  expect_default_is_the_medium(std::string("Material \"subsurface\" ") + kCoefficients, "Shape \"sphere\"\n", 256,
                               0.05);
}

TEST(SubsurfaceDefaultBoundary, ACoefficientGivenThinSlabRendersTheMediumItDescribes) {
  expect_default_is_the_medium(std::string("Material \"subsurface\" ") + kCoefficients, kSlab, 256, 0.05);
}

// pbrt-v4's measured media (per mm, the sphere 2 mm across): the walk's default is the medium.
TEST(SubsurfaceDefaultBoundary, NamedMediaRenderTheMediumTheyName) {
  for (const char* name : {"Skin1", "Marble", "Ketchup"}) {
    SCOPED_TRACE(name);
    expect_default_is_the_medium(std::string("Material \"subsurface\" \"string name\" \"") + name + "\"",
                                 "Shape \"sphere\"\n", 128, 0);
  }
}

// The comparison sees what the default was before: the `diffuse` boundary on the same
// coefficients reads brighter than the medium by many standard errors in the image's mean.
TEST(SubsurfaceDefaultBoundary, TheDiffuseBoundaryOnCoefficientsIsAnotherPicture) {
  const std::string material = std::string("Material \"subsurface\" ") + kCoefficients;
  const auto diffuse = render(kHeader + material + " \"string boundary\" \"diffuse\"\nShape \"sphere\"\n", 256, 41);
  const auto exact = render(kHeader + material + " \"string method\" \"volumetric\"\nShape \"sphere\"\n", 256, 42);
  double largest_z = 0;
  for (const testing::RegionComparison& r : testing::region_comparisons(diffuse, exact, 16, 16))
    largest_z = std::max(largest_z, r.z());
  EXPECT_GT(largest_z, 6) << "the diffuse boundary should read brighter than the medium in some channel";
}

// A scene whose walks got different boundaries by default says so, in one line naming each
// material; a scene of one parametrisation says nothing.
TEST(SubsurfaceDefaultBoundary, MixedParametrisationsAreNamedInOneLine) {
  const std::string coefficients = std::string("Material \"subsurface\" ") + kCoefficients + "\nShape \"sphere\"\n";
  const std::string reflectance =
      "Material \"subsurface\" \"rgb reflectance\" [0.8 0.6 0.5] \"rgb mfp\" [0.5 0.3 0.2]\n"
      "Translate 2.5 0 0\nShape \"sphere\"\n";
  auto notes = [](const std::string& scene) {
    Diagnostics diag;
    build_render_scene(parse_scene_string(scene), diag);
    std::vector<std::string> out;
    for (const std::string& w : diag.warnings)
      if (w.rfind("note:", 0) == 0) out.push_back(w);
    return out;
  };
  const auto mixed = notes(kHeader + coefficients + reflectance);
  ASSERT_EQ(mixed.size(), 1u);
  EXPECT_NE(mixed[0].find("dielectric (coefficients)"), std::string::npos) << mixed[0];
  EXPECT_NE(mixed[0].find("diffuse (reflectance + mfp)"), std::string::npos) << mixed[0];
  EXPECT_TRUE(notes(kHeader + coefficients).empty());
  EXPECT_TRUE(notes(kHeader + reflectance).empty());
}

// Beside a point, spot or distant light a coefficient-given material keeps the diffuse
// boundary (a walk behind a smooth dielectric never sees such a light), and says so.
TEST(SubsurfaceDefaultBoundary, DeltaLightsKeepTheDiffuseBoundary) {
  for (const char* light : {"LightSource \"point\" \"rgb I\" [5 5 5] \"point3 from\" [2 -2 3]\n",
                            "LightSource \"distant\" \"point3 from\" [1 -1 1] \"point3 to\" [0 0 0]\n"}) {
    SCOPED_TRACE(light);
    Diagnostics diag;
    auto sc = build_render_scene(
        parse_scene_string(kHeader + light + "Material \"subsurface\" " + kCoefficients + "\nShape \"sphere\"\n"),
        diag);
    ASSERT_EQ(sc->subsurface_params.size(), 1u);
    EXPECT_EQ(sc->subsurface_params[0].boundary, SubsurfaceParams::Boundary::Diffuse);
    int notes = 0;
    for (const std::string& w : diag.warnings)
      notes += w.rfind("note:", 0) == 0 && w.find("diffuse (coefficients, beside delta lights)") != std::string::npos;
    EXPECT_EQ(notes, 1);
  }
}

}  // namespace
}  // namespace dermis
