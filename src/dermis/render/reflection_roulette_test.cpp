// The camera's first smooth reflection, split off at a subsurface entry and at glass, goes
// on with probability about F where it cannot see a bright emitter (integrator.cpp,
// reflection_survival, Russian roulette on the branch's throughput): the picture is that of
// following it always, region by region within 4 standard errors. Under a bright sky the
// reflection is a tenth of the sphere's light and more at its rim. Checked against a
// broken weight (the surviving reflection not divided by its probability): the whole
// image fails by 15 sigma (walk and probes) and 31 sigma (glass).
#include <gtest/gtest.h>

#include <string>

#include "support/lit_sphere_scene.h"

namespace dermis {
namespace {

TEST(ReflectionRoulette, KeepsThePictureAtSubsurfaceEntriesAndGlass) {
  const std::string header = testing::lit_sphere_header(16, "LightSource \"infinite\" \"rgb L\" [3 3 3]\n");
  const char* kCoefficients = R"("rgb sigma_a" [0.05 0.15 0.3] "rgb sigma_s" [2 3 4] "float g" 0.3)";
  for (const std::string& object :
       {std::string("Material \"subsurface\" ") + kCoefficients + " \"float eta\" 1.4 \"string method\" \"randomwalk\"\n",
        std::string("Material \"subsurface\" ") + kCoefficients +
            " \"float eta\" 1.4 \"string method\" \"disk\" \"string profile\" \"burley\"\n",
        std::string("Material \"dielectric\" \"float eta\" 1.5\n")}) {
    SCOPED_TRACE(object);
    Diagnostics diag;
    auto sc = build_render_scene(parse_scene_string(header + object + "Shape \"sphere\"\n"), diag);
    PathStart always;
    always.reflection_roulette = false;
    const auto a = testing::pixel_statistics(*sc, 256, 81);
    const auto b = testing::pixel_statistics(*sc, 256, 82, always);
    testing::expect_same_region_means(a, b, 4, 4);
    testing::expect_same_region_means(a, b, 16, 16);  // the whole image as one region
  }
}

}  // namespace
}  // namespace dermis
