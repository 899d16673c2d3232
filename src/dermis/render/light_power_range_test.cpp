// A light whose power is beyond the range of 32-bit floats is refused at its directive
// with the formula and what to lower (light selection used to stop the render with
// "Distribution1D: value 0 of the function is inf", naming neither the light nor where
// it is); lights near that range but within it, and lights at infinity of any radiance
// the parser accepts, in a scene of any extent the renderer accepts, assemble.
#include "dermis/render/light_power_range.h"

#include <gtest/gtest.h>

#include <string>

#include "dermis/render/image.h"
#include "dermis/render/scene_assembly.h"
#include "dermis/scene/parser.h"
#include "dermis/scene/scene_test_util.h"

namespace dermis {
namespace {

// The message of the SceneError assembling `world` throws, "" if none.
std::string assembly_error(const std::string& world) {
  Diagnostics diag;
  try {
    assemble_scene(parse_scene_string("LookAt 0 0 5  0 0 0  0 1 0\nCamera \"perspective\"\nFilm \"rgb\" "
                                      "\"integer xresolution\" 4 \"integer yresolution\" 4\nWorldBegin\n" +
                                          world,
                                      "bright.pbrt"),
                   diag);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "";
}

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

TEST(LightPowerRange, PointAndSpotLightsAreCheckedAtTheirDirective) {
  // 4 pi x 2.7e37 = 3.39e38, just inside float's 3.40e38; 2.71e37 is just beyond.
  EXPECT_EQ(assembly_error("LightSource \"point\" \"rgb I\" [2.7e37 2.7e37 2.7e37]\nShape \"sphere\"\n"), "");
  std::string err = assembly_error("Shape \"sphere\"\nLightSource \"point\" \"rgb I\" [2.71e37 2.71e37 2.71e37]\n");
  EXPECT_TRUE(contains(err,
                       "bright.pbrt:6:1: error: the point light's power 4π·I = 4π × 2.71e+37 = 3.41e+38 is "
                       "beyond the range of 32-bit floats (3.4e+38)"))
      << err;
  EXPECT_TRUE(contains(err, "lower \"I\" or \"scale\"")) << err;
  // Each factor in range, the product I x scale too (the parser's check), the power not.
  err = assembly_error("LightSource \"point\" \"rgb I\" [1e30 1e30 1e30] \"float scale\" 1e8\n");
  EXPECT_TRUE(contains(err, "bright.pbrt:5:1: error: the point light's power 4π·I = 4π × 1e+38")) << err;
  // Channels whose float sum overflows: their mean is taken in double.
  err = assembly_error("LightSource \"point\" \"rgb I\" [3e38 3e38 3e38]\n");
  EXPECT_TRUE(contains(err, "4π × 3e+38 = 3.77e+39")) << err;
  // A spot light's power is 2 pi I (1 - (cos start + cos end) / 2): a hemisphere (90
  // degrees, no falloff) gives 2 pi I, beyond for I = 1e38; a narrow cone does not.
  err =
      assembly_error("LightSource \"spot\" \"rgb I\" [1e38 1e38 1e38] \"float coneangle\" 90 \"float conedelta\" 0\n");
  EXPECT_TRUE(contains(err, "bright.pbrt:5:1: error: the spot light's power")) << err;
  EXPECT_TRUE(contains(err, "= 6.28e+38 (I = 1e+38)")) << err;
  EXPECT_EQ(assembly_error("LightSource \"spot\" \"rgb I\" [1e38 1e38 1e38] \"float coneangle\" 5\n"), "");
}

TEST(LightPowerRange, AreaLightsAreCheckedAtTheirShapeOverAllItsTriangles) {
  // Two triangles of area 2e10 each, L = 3e27: each pi L A = 1.9e38 is in range, the
  // shape's 3.8e38 is not.
  const std::string quad =
      "Shape \"trianglemesh\" \"point3 P\" [-1e5 0 -1e5 1e5 0 -1e5 1e5 0 1e5 -1e5 0 1e5] "
      "\"integer indices\" [0 1 2 0 2 3]\n";
  std::string err = assembly_error("AttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [3e27 3e27 3e27]\n" + quad +
                                   "AttributeEnd\n");
  EXPECT_TRUE(contains(err,
                       "bright.pbrt:7:1: error: the area light's power π·L·A = π × 3e+27 × 4e+10 = 3.77e+38 is "
                       "beyond the range of 32-bit floats"))
      << err;
  EXPECT_TRUE(contains(err, "lower \"L\" or \"scale\" (or the shape's size)")) << err;
  EXPECT_EQ(assembly_error("AreaLightSource \"diffuse\" \"rgb L\" [1e27 1e27 1e27]\n" + quad), "");
  // Two-sided: twice the power.
  err = assembly_error("AreaLightSource \"diffuse\" \"rgb L\" [2e27 2e27 2e27] \"bool twosided\" true\n" + quad);
  EXPECT_TRUE(contains(err, "= 5.03e+38 (two-sided: twice π·L·A)")) << err;
  // A sphere: 4 pi^2 r^2 L.
  err =
      assembly_error("AreaLightSource \"diffuse\" \"rgb L\" [1e30 1e30 1e30]\nShape \"sphere\" \"float radius\" 1e4\n");
  EXPECT_TRUE(
      contains(err, "bright.pbrt:6:1: error: the area light's power 4π²·r²·L = 4π² × 1e+04² × 1e+30 = 3.95e+39"))
      << err;
}

TEST(LightPowerRange, LightsAtInfinityOfAnyAcceptedRadianceAssembleInAHugeScene) {
  // pi r^2 L with r = 1e16 and L = 3e38 is far beyond float; only selection uses it, in
  // double. The radiance itself is in range (the parser's check).
  const std::string far = "Translate 0 0 -1e16\nShape \"sphere\" \"float radius\" 1e15\n";
  EXPECT_EQ(assembly_error("LightSource \"distant\" \"rgb L\" [3e38 3e38 3e38]\n" + far), "");
  EXPECT_EQ(assembly_error("LightSource \"infinite\" \"rgb L\" [3e38 3e38 3e38]\n" + far), "");
  EXPECT_EQ(assembly_error("LightSource \"infinite\" \"rgb L\" [3e38 3e38 3e38]\nLightSource \"point\"\n" + far), "");
}

TEST(LightPowerRange, AnImageSkyBeyondFloatsIsRefusedAtItsDirectiveNamingThePixel) {
  test::TempDir dir;
  Image img;
  img.width = img.height = 4;
  img.pixels.assign(4 * 4 * 3, 0.5f);
  for (int c = 0; c < 3; ++c) img.pixels[3 * (2 * 4 + 1) + c] = 10;  // pixel (1, 2)
  write_image(dir.path() + "/sky.exr", img);
  const std::string light = "LightSource \"infinite\" \"string filename\" \"" + dir.path() + "/sky.exr\"";
  // 10 x 1e37 x 4 pi (an equal-area texel's solid angle density) is beyond float.
  std::string err = assembly_error("Shape \"sphere\"\n" + light + " \"float scale\" 1e37\n");
  EXPECT_TRUE(contains(err, "bright.pbrt:6:1: error: infinite light")) << err;
  EXPECT_TRUE(contains(err, "pixel (1, 2) of luminance 10 times the scale 1e+37")) << err;
  EXPECT_TRUE(contains(err, "lower \"scale\"")) << err;
  EXPECT_FALSE(contains(err, "Distribution")) << err;
  EXPECT_EQ(assembly_error("Shape \"sphere\"\n" + light + " \"float scale\" 1e36\n"), "");
}

}  // namespace
}  // namespace dermis
