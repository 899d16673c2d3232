// A textured boundary roughness on `subsurface` (render/subsurface/boundary_roughness.h):
// evaluated at every point where light crosses the boundary. Region means of two
// renders agree within 4 standard errors (of the difference):
// - a constant texture renders as the same constant, for the walk (both boundaries),
//   the disk probes and the volumetric reference, with (reflectance, mfp) given so that
//   the walk's and the reference's albedo inversions are the interpolated ones (at a
//   node of both alpha grids, where the interpolation is exact);
// - a checkerboard of two roughnesses under the walk equals a medium inside a dielectric
//   with the same texture (the `dielectric` material's own textured roughness), and so
//   does a slab whose two faces differ: the walk takes the roughness of each exit point,
//   not of its entry.
#include <gtest/gtest.h>

#include <string>

#include "dermis/render/scene_preparation.h"
#include "dermis/render/volumetric_texture.h"
#include "dermis/scene/parser.h"
#include "support/lit_sphere_scene.h"

namespace dermis {
namespace {

const std::string kHeader = testing::lit_sphere_header(
    16, "LightSource \"distant\" \"point3 from\" [1 -1 2] \"point3 to\" [0 0 0] \"rgb L\" [2 2 2]\n");

void expect_same_picture(const std::string& a, const std::string& b, int spp) {
  testing::expect_same_picture(a, b, spp, 41);
}

// Roughness 0.0625: alpha 0.25, a node of the exit-lobe tables ((k / 16)^2) and of the albedo
// inversions (k / 4).
TEST(SubsurfaceTexturedRoughness, AConstantTextureRendersAsTheConstant) {
  const std::string texture = "Texture \"r\" \"float\" \"constant\" \"float value\" 0.0625\n";
  const std::string albedo = R"("rgb reflectance" [0.7 0.5 0.3] "rgb mfp" [0.4 0.3 0.2] "float eta" 1.4 )";
  const std::string coefficients =
      R"("rgb sigma_a" [0.05 0.15 0.3] "rgb sigma_s" [2 3 4] "float g" 0.3 "float eta" 1.4 )";
  struct Case {
    const char* what;
    std::string params;
    int spp;
  };
  for (const Case& c : {Case{"walk, dielectric boundary",
                             albedo + R"("string method" "randomwalk" "string boundary" "dielectric")", 64},
                        Case{"walk, diffuse boundary",
                             coefficients + R"("string method" "randomwalk" "string boundary" "diffuse")", 64},
                        Case{"disk", coefficients + R"("string method" "disk")", 64},
                        Case{"volumetric", albedo + R"("string method" "volumetric")", 256}}) {
    SCOPED_TRACE(c.what);
    const std::string textured =
        kHeader + texture + "Material \"subsurface\" " + c.params + " \"texture roughness\" \"r\"\nShape \"sphere\"\n";
    const std::string constant =
        kHeader + "Material \"subsurface\" " + c.params + " \"float roughness\" 0.0625\nShape \"sphere\"\n";
    expect_same_picture(textured, constant, c.spp);
  }
}

// The volumetric reference's medium at an entry point with a constant roughness texture
// is, number for number, the medium of the same constant (its inversion at a node).
TEST(SubsurfaceTexturedRoughness, TheVolumetricMediumAtAnEntryIsTheConstantsMedium) {
  const std::string material =
      R"(Material "subsurface" "rgb reflectance" [0.7 0.5 0.3] "rgb mfp" [0.4 0.3 0.2] "float eta" 1.4 "string method" "volumetric" )";
  Diagnostics diag;
  auto textured =
      build_render_scene(parse_scene_string(kHeader + "Texture \"r\" \"float\" \"constant\" \"float value\" 0.0625\n" +
                                            material + "\"texture roughness\" \"r\"\nShape \"sphere\"\n"),
                         diag);
  auto constant = build_render_scene(
      parse_scene_string(kHeader + material + "\"float roughness\" 0.0625\nShape \"sphere\"\n"), diag);
  ASSERT_EQ(textured->volumetric_media.size(), 1u);
  const int m = textured->volumetric_media[0].medium;
  ASSERT_EQ(textured_volumetric(*textured, m), 0);  // a medium per entry point
  const HomogeneousMedium at_entry = volumetric_medium_at(*textured, 0, SurfaceHit{});
  const HomogeneousMedium& expected = constant->media[std::size_t(constant->volumetric_media[0].medium)];
  for (int c = 0; c < 3; ++c) {
    EXPECT_EQ(at_entry.sigma_a[c], expected.sigma_a[c]) << c;
    EXPECT_EQ(at_entry.sigma_s[c], expected.sigma_s[c]) << c;
  }
}

TEST(SubsurfaceTexturedRoughness, ACheckerboardWalkEqualsAMediumInsideTheSameTexturedDielectric) {
  const std::string texture =
      "Texture \"r\" \"float\" \"checkerboard\" \"float uscale\" 16 \"float vscale\" 8 \"float tex1\" 0.02 \"float "
      "tex2\" 0.6\n";
  const char* coefficients = R"("rgb sigma_a" [0.05 0.15 0.3] "rgb sigma_s" [2 3 4] "float g" 0.3)";
  const std::string walk =
      kHeader + texture + "Material \"subsurface\" " + coefficients +
      R"( "float eta" 1.4 "texture roughness" "r" "string method" "randomwalk" "string boundary" "dielectric")"
      "\nShape \"sphere\"\n";
  const std::string volume = kHeader + texture + "MakeNamedMedium \"m\" \"string type\" \"homogeneous\" " +
                             coefficients + "\nMediumInterface \"m\" \"\"\n" +
                             R"(Material "dielectric" "float eta" 1.4 "texture roughness" "r")" +
                             "\nShape \"sphere\"\n";
  expect_same_picture(walk, volume, 128);
}

// A slab smooth on top and rough below (a checkerboard whose squares are the two faces'
// texture coordinates), seen from below and lit by a wide light above: the camera's paths
// enter through the rough face and leave through the smooth one. A walk that took its
// entry's roughness at its exits would leave through a rough top.
TEST(SubsurfaceTexturedRoughness, ASlabSmoothAboveAndRoughBelowTransmitsAsTheVolumetricReference) {
  const std::string header = R"(LookAt 0 0 -3  0 0 0  0 1 0
Camera "perspective" "float fov" 30
Film "rgb" "integer xresolution" 8 "integer yresolution" 8
Integrator "volpath" "integer maxdepth" 100000
WorldBegin
AttributeBegin
  AreaLightSource "diffuse" "rgb L" [4 4 4]
  Shape "trianglemesh" "point3 P" [-3 -3 2  3 -3 2  3 3 2  -3 3 2] "integer indices" [0 2 1 0 3 2]
AttributeEnd
Texture "r" "float" "checkerboard" "float uscale" 1 "float vscale" 1 "float tex1" 0.0 "float tex2" 0.8
)";
  // Top face (z = 0.25) u in [0.1, 0.4]: tex1; bottom face (z = -0.25) u in [1.1, 1.4]: tex2; the
  // sides (z = 0 band) take either.
  const std::string slab = R"(Shape "trianglemesh" "point3 P" [-2 -2 0.25  2 -2 0.25  2 2 0.25  -2 2 0.25
    -2 -2 -0.25  2 -2 -0.25  2 2 -0.25  -2 2 -0.25]
  "point2 uv" [0.1 0.1  0.4 0.1  0.4 0.4  0.1 0.4  1.1 0.1  1.4 0.1  1.4 0.4  1.1 0.4]
  "integer indices" [0 1 2  0 2 3   4 6 5  4 7 6   0 5 1  0 4 5   1 6 2  1 5 6   2 7 3  2 6 7   3 4 0  3 7 4]
)";
  const char* coefficients = R"("rgb sigma_a" [0.05 0.15 0.3] "rgb sigma_s" [2 3 4] "float g" 0.3)";
  const std::string walk =
      header + "Material \"subsurface\" " + coefficients +
      R"( "float eta" 1.4 "texture roughness" "r" "string method" "randomwalk" "string boundary" "dielectric")"
      "\n" +
      slab;
  const std::string volume = header + "MakeNamedMedium \"m\" \"string type\" \"homogeneous\" " + coefficients +
                             "\nMediumInterface \"m\" \"\"\n" +
                             R"(Material "dielectric" "float eta" 1.4 "texture roughness" "r")" + "\n" + slab;
  expect_same_picture(walk, volume, 256);
}

}  // namespace
}  // namespace dermis
