// pbrt-v4's grid media as the parser records them, and their errors.
#include <gtest/gtest.h>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "dermis/scene/parser.h"
#include "dermis/scene/scene_test_util.h"

namespace dermis {
namespace {

using test::has_warning;
using test::parse_world;

// A grid's values (rgbgrid: three floats per colour); none when not given.
std::vector<float> floats(const std::shared_ptr<const FloatArray>& grid) {
  return grid ? std::vector<float>(grid->begin(), grid->end()) : std::vector<float>{};
}

// The world `body` is refused with a SceneError at line:column whose message holds `what`.
void error_at(const std::string& body, int line, int column, const std::string& what) {
  try {
    parse_world(body);
    ADD_FAILURE() << "no error for " << body;
  } catch (const SceneError& e) {
    EXPECT_EQ(e.loc().line, line) << e.what();
    EXPECT_EQ(e.loc().column, column) << e.what();
    EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
  }
}

TEST(ParserGridMedia, UniformgridRgbgridAndCloud) {
  SceneDesc s = parse_world(
      "Translate 1 2 3\n"
      "MakeNamedMedium \"smoke\" \"string type\" \"uniformgrid\" \"integer nx\" 3 \"integer ny\" 2 \"integer nz\" 1\n"
      "  \"float density\" [0 1 2 3 4 5] \"point3 p0\" [1 1 1] \"point3 p1\" [0 2 -1] \"rgb sigma_a\" [1 2 3]\n"
      "  \"float scale\" 2 \"float g\" 0.5\n"
      "MakeNamedMedium \"tint\" \"string type\" \"rgbgrid\" \"integer nx\" 2\n"
      "  \"rgb sigma_s\" [1 2 3 4 5 6]\n"
      "MakeNamedMedium \"sky\" \"string type\" \"cloud\" \"float wispiness\" 0.5 \"spectrum sigma_s\" [400 1 700 2]\n");
  ASSERT_EQ(s.media.size(), 3u);
  const MediumDesc& smoke = s.media[0];
  EXPECT_EQ(smoke.type, "uniformgrid");
  EXPECT_EQ(smoke.nx, 3);
  EXPECT_EQ(smoke.ny, 2);
  EXPECT_EQ(smoke.nz, 1);
  EXPECT_EQ(floats(smoke.density), (std::vector<float>{0, 1, 2, 3, 4, 5}));
  EXPECT_EQ(smoke.p0, Vec3(0, 1, -1));  // the corners in any order, as pbrt-v4's Bounds3f
  EXPECT_EQ(smoke.p1, Vec3(1, 2, 1));
  EXPECT_EQ(smoke.sigma_a, RGB(1, 2, 3));
  EXPECT_EQ(smoke.sigma_s, RGB(1, 1, 1));  // pbrt-v4's default
  EXPECT_FLOAT_EQ(smoke.scale, 2);
  EXPECT_FLOAT_EQ(smoke.g, 0.5f);
  EXPECT_EQ(smoke.medium_to_world.point(Vec3(0, 0, 0)), Vec3(1, 2, 3));
  const MediumDesc& tint = s.media[1];
  EXPECT_FALSE(tint.sigma_a_grid);
  EXPECT_EQ(floats(tint.sigma_s_grid), (std::vector<float>{1, 2, 3, 4, 5, 6}));
  const MediumDesc& sky = s.media[2];
  EXPECT_EQ(sky.type, "cloud");
  EXPECT_FLOAT_EQ(sky.wispiness, 0.5f);
  EXPECT_FLOAT_EQ(sky.frequency, 5);
  EXPECT_GE(sky.sigma_s_data, 0);
  EXPECT_FALSE(has_warning(s, "medium"));
  EXPECT_FALSE(has_warning(s, "unused"));
}

TEST(ParserGridMedia, Emission) {
  SceneDesc s = parse_world(
      "MakeNamedMedium \"fire\" \"string type\" \"uniformgrid\" \"integer nx\" 2 \"float density\" [1 1]\n"
      "  \"rgb Le\" [1 0.5 0] \"float Lescale\" [0 3]\n"
      "MakeNamedMedium \"glow\" \"string type\" \"rgbgrid\" \"rgb sigma_a\" [1 1 1] \"rgb Le\" [0 1 2] \"float "
      "Lescale\" 4\n"
      "MakeNamedMedium \"hot\" \"string type\" \"uniformgrid\" \"float density\" [1] \"float temperature\" [2000]\n"
      "  \"float temperaturecutoff\" 100 \"float temperaturescale\" 2\n");
  EXPECT_EQ(s.media[0].Le, RGB(1, 0.5f, 0));
  EXPECT_EQ(floats(s.media[0].le_scale_grid), (std::vector<float>{0, 3}));
  EXPECT_EQ(floats(s.media[1].Le_grid), (std::vector<float>{0, 1, 2}));
  EXPECT_FLOAT_EQ(s.media[1].Lescale, 4);
  EXPECT_EQ(floats(s.media[2].temperature), (std::vector<float>{2000}));
  EXPECT_FLOAT_EQ(s.media[2].temperature_offset, 100);  // pbrt-v4's alias of temperatureoffset
  EXPECT_FLOAT_EQ(s.media[2].temperature_scale, 2);
  EXPECT_FALSE(has_warning(s, "unused"));
  EXPECT_THROW(
      parse_world("MakeNamedMedium \"m\" \"string type\" \"rgbgrid\" \"rgb sigma_s\" [1 1 1] \"rgb Le\" [1 1 1]\n"),
      SceneError);  // pbrt-v4: Le needs sigma_a
  EXPECT_THROW(
      parse_world("MakeNamedMedium \"m\" \"string type\" \"uniformgrid\" \"integer nx\" 2 \"float density\" [1 1] "
                  "\"float Lescale\" [1]\n"),
      SceneError);  // a count that is not the grid's
}

TEST(ParserGridMedia, BadGridsAreErrorsAtTheValue) {
  const std::string grid = "MakeNamedMedium \"m\" \"string type\" \"uniformgrid\" ";
  error_at(grid + "\"integer nx\" 2 \"float density\" [1 2 3]\n", 2, 80, "\"density\" has 3 values; the grid nx x ny");
  error_at(grid + "\"integer nx\" 3 \"float density\" [1 -2 3]\n", 2, 83, "must be finite and at least 0 (value 1");
  error_at(grid + "\"float density\" [1]\n\"point3 p0\" [0 0 0] \"point3 p1\" [1 0 1]\n", 3, 33, "has no volume");
  error_at(grid + "\"integer nx\" 2\n", 2, 1, "needs \"float density\"");
  error_at(grid + "\"integer nx\" 0 \"float density\" [1]\n", 2, 62, "\"nx\" must be at least 1");
  error_at(grid + "\"float density\" [1] \"rgb sigma_a\" [1 -1 1]\n", 2, 83, "\"sigma_a\" must not be negative");
  error_at("MakeNamedMedium \"m\" \"string type\" \"rgbgrid\" \"integer nx\" 2\n", 2, 1,
           "needs \"rgb sigma_a\" and/or \"rgb sigma_s\"");
  error_at("MakeNamedMedium \"m\" \"string type\" \"rgbgrid\" \"rgb sigma_a\" [1 2 3 4 5 6]\n", 2, 59,
           "\"sigma_a\" has 2 values");
}

// A grid longer than kLongNumberList values is read as floats (once), and its errors still
// point at the offending value.
TEST(ParserGridMedia, LongGridsAreFloatsAndErrorsAtTheValue) {
  constexpr int n = 20;  // 8000 densities, 24000 colour floats: past kLongNumberList
  auto medium = [](const std::string& type, const std::string& param, int per_cell, std::size_t bad) {
    std::string text = "MakeNamedMedium \"" + type + "\" \"string type\" \"" + type +
                       "\" \"integer nx\" 20 \"integer ny\" 20 \"integer nz\" 20 \"" + param + "\" [\n";
    for (std::size_t i = 0; i < std::size_t(n * n * n * per_cell); ++i)
      text += i == bad ? "-2\n" : std::to_string(i % 7) + ".1\n";  // value i on line 3 + i
    return text + "]\n";
  };
  const SceneDesc s =
      parse_world(medium("uniformgrid", "float density", 1, SIZE_MAX) + medium("rgbgrid", "rgb sigma_s", 3, SIZE_MAX));
  const std::vector<float> density = floats(s.media[0].density), sigma_s = floats(s.media[1].sigma_s_grid);
  ASSERT_EQ(density.size(), 8000u);
  ASSERT_EQ(sigma_s.size(), 24000u);
  EXPECT_EQ(density[7999], float(7999 % 7 + 0.1));
  EXPECT_EQ(sigma_s[23999], float(23999 % 7 + 0.1));
  error_at(medium("uniformgrid", "float density", 1, 6000), 6003, 1, "(value 6000 of the grid is -2)");
  error_at(medium("rgbgrid", "rgb sigma_s", 3, 20000), 20003, 1, "(value 6666 of the grid is -2)");
}

// A subsurface material's "interior" names a medium: a homogeneous one's coefficients (scale
// applied), spectra and g become the material's; a grid one's index is kept for the random
// walk and the volumetric reference, whatever comes first.
TEST(ParserSubsurfaceInterior, HomogeneousCopiedGridKept) {
  SceneDesc s = parse_world(
      "MakeNamedMedium \"jade\" \"string type\" \"homogeneous\" \"rgb sigma_a\" [1 2 3] \"rgb sigma_s\" [4 5 6]\n"
      "  \"float scale\" 2 \"float g\" 0.25\n"
      "Material \"subsurface\" \"string interior\" \"jade\"\n"
      "Material \"subsurface\" \"string interior\" \"veins\" \"string method\" \"volumetric\"\n"
      "MakeNamedMedium \"veins\" \"string type\" \"uniformgrid\" \"float density\" [1] \"float g\" -0.5\n");
  ASSERT_EQ(s.materials.size(), 2u);
  const SubsurfaceParams& jade = s.materials[0].subsurface;
  EXPECT_EQ(jade.interior_medium, -1);
  EXPECT_EQ(*jade.sigma_a, RGB(2, 4, 6));
  EXPECT_EQ(*jade.sigma_s, RGB(8, 10, 12));
  EXPECT_FLOAT_EQ(jade.g, 0.25f);
  EXPECT_EQ(jade.boundary, SubsurfaceParams::Boundary::Dielectric);  // coefficients: the physical object
  const SubsurfaceParams& veins = s.materials[1].subsurface;
  EXPECT_EQ(veins.interior_medium, 1);
  EXPECT_FLOAT_EQ(veins.g, -0.5f);
}

TEST(ParserSubsurfaceInterior, ErrorsAtTheName) {
  const std::string grid = "MakeNamedMedium \"g\" \"string type\" \"uniformgrid\" \"float density\" [1]\n";
  error_at("Material \"subsurface\" \"string interior\" \"nowhere\"\n", 2, 41, "unknown medium \"nowhere\"");
  error_at(grid + "Material \"subsurface\" \"string interior\" \"g\" \"string method\" \"disk\"\n", 3, 41,
           "the \"disk\" method cannot follow");
  error_at(grid + "Material \"subsurface\" \"string interior\" \"g\" \"rgb sigma_a\" [1 1 1]\n", 3, 1,
           "or \"interior\", not several");
  error_at(grid + "Material \"subsurface\" \"string interior\" \"g\" \"float scale\" 2\n", 3, 45,
           "\"scale\" does not apply beside \"interior\"");
  error_at("Material \"subsurface\" \"string interior\" [\"a\" \"b\"]\n", 2, 41, "\"interior\" needs one string");
}

}  // namespace
}  // namespace dermis
