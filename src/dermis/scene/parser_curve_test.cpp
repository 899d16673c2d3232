// pbrt-v4's `curve` shape and `hair` material as the parser reads them: parameters,
// defaults, the errors of bad input at their place, the warnings owed.
#include <gtest/gtest.h>

#include "dermis/scene/scene_test_util.h"

namespace dermis {
namespace {

using test::parse_world;

// Lit, so that no "no lights" warning is raised.
SceneDesc parse_lit(const std::string& body) { return parse_world("LightSource \"point\"\n" + body); }

std::string error_of(const std::string& body) {
  try {
    parse_lit(body);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(ParserCurve, DefaultsAreAFlatCubicBezierOfWidthOne) {
  const SceneDesc s = parse_lit("Shape \"curve\" \"point3 P\" [0 0 0 1 1 0 2 1 0 3 0 0] \"integer splitdepth\" 5\n");
  EXPECT_TRUE(s.diagnostics.warnings.empty()) << s.diagnostics.warnings.front();  // splitdepth read, silently
  ASSERT_EQ(s.shapes.size(), 1u);
  const ShapeDesc& c = s.shapes[0];
  EXPECT_EQ(c.type, ShapeDesc::Type::Curve);
  EXPECT_EQ(c.curve.kind, CurveKind::Flat);
  ASSERT_EQ(c.curve.segment_count(), 1u);
  for (float w : c.curve.widths) EXPECT_EQ(w, 1.0f);
  EXPECT_EQ(c.curve.points[2].x, 2.0f);
}

TEST(ParserCurve, TypesBasesDegreesAndWidths) {
  const SceneDesc s = parse_lit(
      "Shape \"curve\" \"string type\" \"cylinder\" \"string basis\" \"bspline\" \"integer degree\" 2\n"
      "  \"point3 P\" [0 0 0 1 1 0 2 1 0 3 0 0 4 0 0] \"float width0\" 0.5 \"float width1\" 0.1\n"
      "Shape \"curve\" \"string type\" \"ribbon\" \"point3 P\" [0 0 0 1 0 0 2 0 0 3 0 0 4 0 0 5 0 0 6 0 0]\n"
      "  \"normal N\" [0 0 1 0 1 1 0 1 0] \"float width\" 0.2\n");
  EXPECT_TRUE(s.diagnostics.warnings.empty());
  ASSERT_EQ(s.shapes.size(), 2u);
  EXPECT_EQ(s.shapes[0].curve.kind, CurveKind::Cylinder);
  EXPECT_EQ(s.shapes[0].curve.segment_count(), 3u);  // 5 points, degree 2 B-spline
  EXPECT_FLOAT_EQ(s.shapes[0].curve.widths.front(), 0.5f);
  EXPECT_FLOAT_EQ(s.shapes[0].curve.widths.back(), 0.1f);
  EXPECT_EQ(s.shapes[1].curve.kind, CurveKind::Ribbon);
  EXPECT_EQ(s.shapes[1].curve.segment_count(), 2u);
  ASSERT_EQ(s.shapes[1].curve.normals.size(), 8u);
  EXPECT_NEAR(s.shapes[1].curve.normals[3].y, std::sqrt(0.5f), 1e-6f);  // normalised
}

TEST(ParserCurve, BadInputIsAnErrorAtItsValue) {
  EXPECT_NE(error_of("Shape \"curve\" \"point3 P\" [0 0 0 1 0 0 2 0 0 3 0 0 4 0 0]\n").find("test.pbrt:3:"),
            std::string::npos);
  EXPECT_NE(error_of("Shape \"curve\" \"point3 P\" [0 0 0 1 0 0 2 0 0 3 0 0 4 0 0]\n").find("4 + n * 3"),
            std::string::npos);
  EXPECT_NE(error_of("Shape \"curve\" \"point3 P\" [0 0 0 1 0 0 2 0 0 3 0 0] \"string type\" \"tube\"\n")
                .find("test.pbrt:3:66: error: curve \"type\" \"tube\" is not one of flat, cylinder, ribbon"),
            std::string::npos);
  EXPECT_NE(error_of("Shape \"curve\" \"point3 P\" [0 0 0 1 0 0 2 0 0 3 0 0] \"string basis\" \"catmullrom\"\n")
                .find("is not one of bezier, bspline"),
            std::string::npos);
  EXPECT_NE(error_of("Shape \"curve\" \"point3 P\" [0 0 0 1 0 0 2 0 0 3 0 0] \"integer degree\" 4\n")
                .find("degree must be 2 or 3"),
            std::string::npos);
  EXPECT_NE(error_of("Shape \"curve\" \"point3 P\" [0 0 0 1 0 0 2 0 0 3 0 0] \"string type\" \"ribbon\"\n")
                .find("needs 2 normals"),
            std::string::npos);
  EXPECT_NE(error_of("Shape \"curve\" \"point3 P\" [0 0 0 1 0 0 2 0 0 3 0 0] \"float width\" -1\n")
                .find("\"width\" must be finite and >= 0"),
            std::string::npos);
  EXPECT_NE(error_of("Shape \"curve\"\n").find("needs \"point3 P\""), std::string::npos);
}

TEST(ParserCurve, WarnedOnce) {
  // Normals on a curve that is not a ribbon: ignored, as pbrt-v4.
  const SceneDesc a = parse_lit("Shape \"curve\" \"point3 P\" [0 0 0 1 0 0 2 0 0 3 0 0] \"normal N\" [0 0 1 0 0 1]\n");
  ASSERT_EQ(a.diagnostics.warnings.size(), 1u);
  EXPECT_NE(a.diagnostics.warnings[0].find("used only by \"ribbon\" curves"), std::string::npos);
  EXPECT_TRUE(a.shapes[0].curve.normals.empty());
  // An area light on a curve: not emissive, as pbrt-v4 cannot sample curves either.
  const SceneDesc b =
      parse_lit("AreaLightSource \"diffuse\"\nShape \"curve\" \"point3 P\" [0 0 0 1 0 0 2 0 0 3 0 0]\n");
  ASSERT_EQ(b.diagnostics.warnings.size(), 1u);
  EXPECT_NE(b.diagnostics.warnings[0].find("test.pbrt:4:1: warning: an area light on a curve"), std::string::npos);
  EXPECT_FALSE(b.shapes[0].area_light.has_value());
}

// pbrt-v4's hair material is not implemented: one warning, none per parameter, and a
// diffuse surface of its "reflectance" (else 0.5).
TEST(ParserHair, OneWarningAndADiffuseFallback) {
  const SceneDesc s = parse_lit(
      "Material \"hair\" \"float eumelanin\" 8 \"float pheomelanin\" 0.2 \"float beta_m\" 0.3 \"float beta_n\" 0.3\n"
      "  \"float alpha\" 2 \"float eta\" 1.55\n"
      "Shape \"curve\" \"point3 P\" [0 0 0 1 0 0 2 0 0 3 0 0]\n"
      "Material \"hair\" \"rgb reflectance\" [0.6 0.3 0.1]\n"
      "Shape \"curve\" \"point3 P\" [0 0 0 1 0 0 2 0 0 3 0 0]\n");
  ASSERT_EQ(s.diagnostics.warnings.size(), 2u);
  for (const std::string& w : s.diagnostics.warnings)
    EXPECT_NE(w.find("material \"hair\" is not supported: rendered as diffuse"), std::string::npos) << w;
  EXPECT_NE(s.diagnostics.warnings[0].find("test.pbrt:3:1"), std::string::npos);
  ASSERT_EQ(s.materials.size(), 2u);
  EXPECT_EQ(s.materials[0].type, MaterialDesc::Type::Diffuse);
  EXPECT_FLOAT_EQ(s.materials[0].reflectance.value[0], 0.5f);
  EXPECT_FLOAT_EQ(s.materials[1].reflectance.value[1], 0.3f);
  // A misspelt parameter is still warned.
  EXPECT_EQ(parse_lit("Material \"hair\" \"float eumelanine\" 1\n").diagnostics.warnings.size(), 2u);
}

}  // namespace
}  // namespace dermis
