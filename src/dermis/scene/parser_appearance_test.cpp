// Materials, textures, lights, media and spectra as the parser records them.
#include <gtest/gtest.h>

#include "dermis/scene/parser.h"
#include "dermis/scene/scene_test_util.h"
#include "dermis/scene/spectra.h"

namespace dermis {
namespace {

using test::has_warning;
using test::parse_world;

void expect_rgb(RGB a, RGB b, float tol = 1e-6f) {
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(a[i], b[i], tol) << "channel " << i;
}

TEST(ParserMaterials, DiffuseAndDefaults) {
  SceneDesc s = parse_world(
      "Material \"diffuse\" \"rgb reflectance\" [0.1 0.2 0.3]\nShape \"sphere\"\n"
      "Material \"diffuse\"\nShape \"sphere\"\n");
  ASSERT_EQ(s.materials.size(), 2u);
  EXPECT_EQ(s.materials[0].type, MaterialDesc::Type::Diffuse);
  expect_rgb(s.materials[0].reflectance.value, RGB(0.1f, 0.2f, 0.3f));
  expect_rgb(s.materials[1].reflectance.value, RGB(0.5f));
  EXPECT_EQ(s.shapes[0].material, 0);
  EXPECT_EQ(s.shapes[1].material, 1);
}

TEST(ParserMaterials, DielectricEtaFloatNamedAndRoughness) {
  SceneDesc s = parse_world(
      "Material \"dielectric\" \"float eta\" 1.33\n"
      "Material \"dielectric\" \"spectrum eta\" \"glass-BK7\" \"float roughness\" 0.2\n"
      "Material \"dielectric\"\n");
  EXPECT_EQ(s.materials[0].type, MaterialDesc::Type::Dielectric);
  EXPECT_FLOAT_EQ(s.materials[0].eta, 1.33f);
  EXPECT_NEAR(s.materials[1].eta, 1.5196f, 1e-4);  // BK7: n_d = 1.5168; mean over 400-700 nm
  EXPECT_FLOAT_EQ(s.materials[1].roughness, 0.2f);
  EXPECT_FLOAT_EQ(s.materials[1].uroughness, 0.2f);  // rendered rough: no warning
  EXPECT_FLOAT_EQ(s.materials[1].vroughness, 0.2f);
  EXPECT_TRUE(s.materials[1].remap_roughness);
  EXPECT_FALSE(has_warning(s, "roughness"));
  EXPECT_FLOAT_EQ(s.materials[0].uroughness, 0.0f);  // smooth by default
  EXPECT_FLOAT_EQ(s.materials[2].eta, 1.5f);
}

// pbrt-v4's DielectricMaterial / ConductorMaterial::Create: "roughness" sets both axes,
// "uroughness" / "vroughness" override it; "remaproughness" defaults to true.
TEST(ParserMaterials, MicrofacetRoughness) {
  SceneDesc s = parse_world(
      "Material \"dielectric\" \"float roughness\" 0.3 \"float vroughness\" 0.05\n"
      "Material \"conductor\" \"float uroughness\" 0.1 \"float vroughness\" 0.4 \"bool remaproughness\" false\n"
      "Material \"thindielectric\" \"float roughness\" 0.2\n"
      "Texture \"r\" \"float\" \"constant\" \"float value\" 0.5\n"
      "Material \"conductor\" \"texture roughness\" \"r\" \"float vroughness\" 0.1\n"
      "Material \"coateddiffuse\" \"float roughness\" 0.3\n");
  const MaterialDesc& d = s.materials[0];
  EXPECT_EQ(d.type, MaterialDesc::Type::Dielectric);
  EXPECT_FLOAT_EQ(d.uroughness, 0.3f);
  EXPECT_FLOAT_EQ(d.vroughness, 0.05f);
  EXPECT_TRUE(d.remap_roughness);
  const MaterialDesc& c = s.materials[1];
  EXPECT_EQ(c.type, MaterialDesc::Type::Conductor);
  EXPECT_FLOAT_EQ(c.uroughness, 0.1f);
  EXPECT_FLOAT_EQ(c.vroughness, 0.4f);
  EXPECT_FLOAT_EQ(c.roughness, 0.4f);
  EXPECT_FALSE(c.remap_roughness);
  EXPECT_EQ(s.materials[2].type, MaterialDesc::Type::Dielectric);  // thindielectric, as dielectric
  EXPECT_FLOAT_EQ(s.materials[2].uroughness, 0.2f);
  EXPECT_FLOAT_EQ(s.materials[2].vroughness, 0.2f);
  // Textured roughness: the float texture along u (evaluated per hit), the constant along v.
  EXPECT_EQ(s.materials[3].roughness_texture[0], 0);
  EXPECT_EQ(s.materials[3].roughness_texture[1], -1);
  EXPECT_FLOAT_EQ(s.materials[3].vroughness, 0.1f);
  EXPECT_FALSE(has_warning(s, "textured"));
  EXPECT_FALSE(has_warning(s, "dielectric roughness"));
  EXPECT_FALSE(has_warning(s, "conductor roughness"));
  EXPECT_FLOAT_EQ(s.materials[4].uroughness, 0.3f);  // coateddiffuse's interface, rendered rough
  EXPECT_FLOAT_EQ(s.materials[4].vroughness, 0.3f);
  EXPECT_FALSE(has_warning(s, "coateddiffuse"));
  EXPECT_FALSE(has_warning(s, "unused"));
  EXPECT_THROW(parse_world("Material \"dielectric\" \"float uroughness\" -0.1\n"), SceneError);
  EXPECT_THROW(parse_world("Material \"conductor\" \"float remaproughness\" 1\n"), SceneError);
}

TEST(ParserMaterials, ConductorNamedRgbAndReflectance) {
  SceneDesc s = parse_world(
      "Material \"conductor\" \"spectrum eta\" \"metal-Au-eta\" \"spectrum k\" \"metal-Au-k\"\n"
      "Material \"conductor\" \"rgb eta\" [0.2 0.3 0.4] \"rgb k\" [3 2 1]\n"
      "Material \"conductor\" \"rgb reflectance\" [0.9 0.8 0.7]\n"
      "Material \"conductor\"\n");
  EXPECT_EQ(s.materials[0].type, MaterialDesc::Type::Conductor);
  expect_rgb(s.materials[0].conductor_eta, *named_spectrum_rgb("metal-Au-eta"));
  expect_rgb(s.materials[0].conductor_k, *named_spectrum_rgb("metal-Au-k"));
  // Gold: red has a low index and a high extinction; blue the reverse.
  EXPECT_LT(s.materials[0].conductor_eta[0], s.materials[0].conductor_eta[2]);
  EXPECT_GT(s.materials[0].conductor_k[0], s.materials[0].conductor_k[2]);
  expect_rgb(s.materials[1].conductor_eta, RGB(0.2f, 0.3f, 0.4f));
  expect_rgb(s.materials[1].conductor_k, RGB(3, 2, 1));
  EXPECT_TRUE(s.materials[2].has_reflectance);
  expect_rgb(s.materials[2].reflectance.value, RGB(0.9f, 0.8f, 0.7f));
  expect_rgb(s.materials[3].conductor_eta, *named_spectrum_rgb("metal-Cu-eta"));  // pbrt-v4's default
}

TEST(ParserMaterials, InterfaceCoatedSubsurfaceAndUnknown) {
  SceneDesc s = parse_world(
      "Material \"interface\"\nMaterial \"\"\nMaterial \"none\"\n"
      "Material \"coateddiffuse\" \"rgb reflectance\" [0.4 0.4 0.4] \"float roughness\" 0 \"float eta\" 1.4\n"
      "Material \"subsurface\" \"float eta\" 1.4 \"string name\" \"Skin1\" \"float scale\" 10 \"string method\" "
      "\"disk\"\n"
      "Material \"measured\" \"string filename\" \"x.bsdf\"\n");
  for (int i = 0; i < 3; ++i) EXPECT_EQ(s.materials[i].type, MaterialDesc::Type::Interface);
  EXPECT_EQ(s.materials[3].type, MaterialDesc::Type::CoatedDiffuse);
  EXPECT_FLOAT_EQ(s.materials[3].eta, 1.4f);
  expect_rgb(s.materials[3].reflectance.value, RGB(0.4f));
  const MaterialDesc& ss = s.materials[4];
  EXPECT_EQ(ss.type, MaterialDesc::Type::Subsurface);
  EXPECT_FLOAT_EQ(ss.eta, 1.4f);
  // Read once, by the parser (scene/subsurface_params.h): Skin1 per mm, times the scale.
  EXPECT_FLOAT_EQ(ss.subsurface.eta, 1.4f);
  ASSERT_TRUE(ss.subsurface.sigma_a.has_value());
  EXPECT_NEAR((*ss.subsurface.sigma_a)[0], 0.32f, 1e-5f);
  EXPECT_EQ(ss.subsurface.method, SubsurfaceParams::Method::Disk);
  EXPECT_EQ(ss.subsurface.loc.line, 6);
  EXPECT_EQ(s.materials[5].type, MaterialDesc::Type::Diffuse);
  // (hair, once the unsupported material here, is read now: ParserHair.*)
  EXPECT_TRUE(has_warning(s, "test.pbrt:7:1: warning: unsupported material \"measured\""));
  // The unsupported material's parameters are warned, each where it is; no other is unused.
  EXPECT_TRUE(has_warning(s, "test.pbrt:7:21: warning: unused parameter \"string filename\""));
  int unused = 0;
  for (const std::string& w : s.diagnostics.warnings) unused += w.find("unused parameter") != std::string::npos;
  EXPECT_EQ(unused, 1);
}

TEST(ParserMaterials, NamedMaterials) {
  SceneDesc s = parse_world(
      "MakeNamedMaterial \"gold\" \"string type\" \"conductor\"\n"
      "MakeNamedMaterial \"white\" \"string type\" \"diffuse\" \"rgb reflectance\" [1 1 1]\n"
      "NamedMaterial \"white\"\nShape \"sphere\"\nNamedMaterial \"gold\"\nShape \"sphere\"\n");
  ASSERT_EQ(s.materials.size(), 2u);
  EXPECT_EQ(s.materials[0].name, "gold");
  EXPECT_EQ(s.shapes[0].material, 1);
  EXPECT_EQ(s.shapes[1].material, 0);
  EXPECT_FALSE(has_warning(s, "unused"));
}

TEST(ParserTextures, ImageMapConstantScaleAndReference) {
  test::TempDir dir;
  dir.write("tex/wood.png", "not really a png; the renderer reads it");
  SceneDesc s = parse_world(
      "Texture \"wood\" \"spectrum\" \"imagemap\" \"string filename\" \"tex/wood.png\" \"float scale\" 2\n"
      "  \"bool invert\" true \"string encoding\" \"linear\" \"string wrap\" \"clamp\" \"float uscale\" 3\n"
      "  \"float vscale\" 4 \"float udelta\" 0.5 \"float vdelta\" 0.25\n"
      "Texture \"k\" \"spectrum\" \"constant\" \"rgb value\" [0.1 0.2 0.3]\n"
      "Texture \"half\" \"spectrum\" \"scale\" \"texture tex\" \"wood\" \"float scale\" 0.5\n"
      "Texture \"f\" \"float\" \"constant\" \"float value\" 0.7\n"
      "Texture \"odd\" \"spectrum\" \"ptex\" \"float foo\" 1\n"
      "Texture \"check\" \"spectrum\" \"checkerboard\" \"texture tex1\" \"k\" \"float uscale\" 8\n"
      "Texture \"blend\" \"spectrum\" \"mix\" \"texture tex2\" \"k\" \"texture amount\" \"f\"\n"
      "Material \"diffuse\" \"texture reflectance\" \"half\"\n",
      dir.path());
  ASSERT_EQ(s.textures.size(), 7u);
  const TextureDesc& w = s.textures[0];
  EXPECT_EQ(w.type, TextureDesc::Type::ImageMap);
  EXPECT_EQ(w.filename, dir.path() + "/tex/wood.png");
  EXPECT_FLOAT_EQ(w.scale, 2);
  EXPECT_TRUE(w.invert);
  EXPECT_EQ(w.encoding, "linear");
  EXPECT_EQ(w.wrap, "clamp");
  EXPECT_FLOAT_EQ(w.uscale, 3);
  EXPECT_FLOAT_EQ(w.vscale, 4);
  EXPECT_FLOAT_EQ(w.udelta, 0.5f);
  EXPECT_FLOAT_EQ(w.vdelta, 0.25f);
  EXPECT_EQ(s.textures[1].type, TextureDesc::Type::Constant);
  expect_rgb(s.textures[1].value, RGB(0.1f, 0.2f, 0.3f));
  EXPECT_EQ(s.textures[2].type, TextureDesc::Type::Scale);
  EXPECT_EQ(s.textures[2].base, 0);
  EXPECT_FLOAT_EQ(s.textures[2].scale, 0.5f);
  EXPECT_TRUE(s.textures[3].is_float);
  expect_rgb(s.textures[3].value, RGB(0.7f));
  expect_rgb(s.textures[4].value, RGB(1));
  EXPECT_TRUE(
      has_warning(s, "test.pbrt:8:1: warning: ptex textures are not supported; texture \"odd\" is the constant 1"));
  // Its parameters are read by nobody: each warned where it is.
  EXPECT_TRUE(has_warning(s, "test.pbrt:8:33: warning: unused parameter \"float foo\""));
  const TextureDesc& c = s.textures[5];
  EXPECT_EQ(c.type, TextureDesc::Type::Checkerboard);
  EXPECT_EQ(c.tex1, 1);  // "k"
  EXPECT_EQ(c.tex2, -1);
  expect_rgb(c.value2, RGB(0));  // pbrt-v4's default tex2
  EXPECT_FLOAT_EQ(c.uscale, 8);
  const TextureDesc& m = s.textures[6];
  EXPECT_EQ(m.type, TextureDesc::Type::Mix);
  EXPECT_EQ(m.tex2, 1);            // "k"
  EXPECT_EQ(m.amount_texture, 3);  // the float texture "f"
  expect_rgb(m.value, RGB(0));     // pbrt-v4's default tex1
  EXPECT_EQ(s.materials[0].reflectance.texture, 2);
}

// pbrt-v4's parameter names and defaults for the noise textures, dots and directionmix.
TEST(ParserTextures, NoiseDotsAndDirectionMixDefaults) {
  SceneDesc s = parse_world(
      "Translate 1 2 3\n"
      "Texture \"f\" \"float\" \"fbm\"\n"
      "Texture \"w\" \"float\" \"wrinkled\" \"integer octaves\" 3 \"float roughness\" 0.25\n"
      "Texture \"wind\" \"float\" \"windy\"\n"
      "Texture \"m\" \"spectrum\" \"marble\"\n"
      "Texture \"m2\" \"spectrum\" \"marble\" \"float scale\" 4 \"float variation\" 0.5 \"integer octaves\" 2\n"
      "Texture \"d\" \"spectrum\" \"dots\" \"texture inside\" \"m\" \"float uscale\" 6\n"
      "Rotate 90 0 0 1\n"
      "Texture \"dm\" \"float\" \"directionmix\" \"texture tex2\" \"f\"\n"
      "Texture \"sph\" \"spectrum\" \"checkerboard\" \"string mapping\" \"spherical\"\n"
      "Texture \"pl\" \"spectrum\" \"bilerp\" \"string mapping\" \"planar\" \"vector3 v1\" [0 0 1] \"float udelta\" 2\n"
      "Texture \"c3\" \"float\" \"checkerboard\" \"integer dimension\" 3\n");
  ASSERT_EQ(s.textures.size(), 10u);
  const TextureDesc& f = s.textures[0];
  EXPECT_EQ(f.type, TextureDesc::Type::FBm);
  EXPECT_EQ(f.mapping, "3d");
  EXPECT_EQ(f.octaves, 8);
  EXPECT_FLOAT_EQ(f.roughness, 0.5f);
  // The texture's space is the CTM's: world (1, 2, 3) is its origin.
  const Vec3 o = f.texture_from_world.point(Vec3(1, 2, 3));
  EXPECT_NEAR(length(o), 0, 1e-6f);
  EXPECT_EQ(s.textures[1].octaves, 3);
  EXPECT_FLOAT_EQ(s.textures[1].roughness, 0.25f);
  EXPECT_EQ(s.textures[2].type, TextureDesc::Type::Windy);
  const TextureDesc& m = s.textures[3];
  EXPECT_EQ(m.type, TextureDesc::Type::Marble);
  EXPECT_FLOAT_EQ(m.scale, 1);
  EXPECT_FLOAT_EQ(m.variation, 0.2f);
  EXPECT_EQ(m.octaves, 8);
  EXPECT_FLOAT_EQ(s.textures[4].scale, 4);
  EXPECT_FLOAT_EQ(s.textures[4].variation, 0.5f);
  const TextureDesc& d = s.textures[5];
  EXPECT_EQ(d.type, TextureDesc::Type::Dots);
  EXPECT_EQ(d.tex1, 3);          // inside: "m"
  expect_rgb(d.value2, RGB(0));  // outside: pbrt-v4's 0
  EXPECT_EQ(d.mapping, "uv");
  EXPECT_FLOAT_EQ(d.uscale, 6);
  const TextureDesc& dm = s.textures[6];
  EXPECT_EQ(dm.type, TextureDesc::Type::DirectionMix);
  EXPECT_EQ(dm.tex2, 0);
  expect_rgb(dm.value, RGB(0));  // tex1: pbrt-v4's 0
  // dir (0, 1, 0) in the texture's space, rotated 90 degrees about z: world -x.
  EXPECT_NEAR(dm.dir.x, -1, 1e-6f);
  EXPECT_NEAR(dm.dir.y, 0, 1e-6f);
  EXPECT_EQ(s.textures[7].mapping, "spherical");
  EXPECT_EQ(s.textures[8].mapping, "planar");
  EXPECT_NEAR(s.textures[8].v1.z, 1, 1e-6f);
  EXPECT_NEAR(s.textures[8].v2.y, 1, 1e-6f);  // default v2 (0, 1, 0)
  EXPECT_FLOAT_EQ(s.textures[8].udelta, 2);
  EXPECT_EQ(s.textures[9].mapping, "3d");
  EXPECT_FALSE(has_warning(s, "warning: unused"));
  EXPECT_FALSE(has_warning(s, "unsupported"));
}

TEST(ParserTextures, ErrorsAndWarningsOfTheNewClasses) {
  auto error_at = [](const std::string& body, int line, int column, const std::string& what) {
    try {
      parse_world(body);
      ADD_FAILURE() << "no error for " << body;
    } catch (const SceneError& e) {
      EXPECT_EQ(e.loc().line, line) << e.what();
      EXPECT_EQ(e.loc().column, column) << e.what();
      EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
    }
  };
  // fbm, wrinkled, windy are float textures in pbrt-v4; marble a spectrum one.
  error_at("Texture \"a\" \"spectrum\" \"fbm\"\n", 2, 13, "\"fbm\" is a float texture");
  error_at("Texture \"a\" \"float\" \"marble\"\n", 2, 13, "\"marble\" is a spectrum texture");
  error_at("Texture \"a\" \"float\" \"dots\" \"string mapping\" \"cubic\"\n", 2, 45, "texture mapping must be");
  error_at("Texture \"a\" \"float\" \"fbm\" \"integer octaves\" -1\n", 2, 45, "\"octaves\" must be in [0, 64]");
  error_at("Texture \"a\" \"float\" \"directionmix\" \"vector3 dir\" [0 0 0]\n", 2, 50, "non-zero");
  error_at("Texture \"a\" \"float\" \"dots\" \"texture inside\" \"nope\"\n", 2, 45, "unknown float texture \"nope\"");
  // ptex: one warning, a constant; the spherical mapping reads no uscale (warned unused).
  SceneDesc s = parse_world(
      "Texture \"p\" \"spectrum\" \"ptex\" \"string filename\" \"a.ptx\" \"float scale\" 2\n"
      "Texture \"q\" \"float\" \"dots\" \"string mapping\" \"spherical\" \"float uscale\" 2\n");
  EXPECT_EQ(s.textures[0].type, TextureDesc::Type::Constant);
  EXPECT_TRUE(has_warning(s, "test.pbrt:2:1: warning: ptex textures are not supported"));
  EXPECT_EQ(s.diagnostics.warnings.size(), 3u);  // ptex, uscale, no lights
  EXPECT_TRUE(has_warning(s, "test.pbrt:3:57: warning: unused parameter \"float uscale\""));
}

TEST(ParserLights, PointSpotDistantInfinite) {
  test::TempDir dir;
  dir.write("sky.exr", "x");
  SceneDesc s = parse_world(
      "Translate 0 1 0\n"
      "LightSource \"point\" \"rgb I\" [1 2 3] \"float scale\" 4 \"point3 from\" [1 2 3]\n"
      "LightSource \"spot\" \"point3 from\" [0 0 0] \"point3 to\" [0 -1 0] \"float coneangle\" 20 \"float conedelta\" "
      "2\n"
      "LightSource \"distant\" \"blackbody L\" 6500 \"point3 to\" [0 0 -1]\n"
      "LightSource \"infinite\" \"string filename\" \"sky.exr\" \"float power\" 3\n"
      "LightSource \"goniometric\"\n",
      dir.path());
  ASSERT_EQ(s.lights.size(), 4u);
  const LightDesc& p = s.lights[0];
  EXPECT_EQ(p.type, LightDesc::Type::Point);
  expect_rgb(p.spectrum, RGB(1, 2, 3));
  EXPECT_FLOAT_EQ(p.scale, 4);
  EXPECT_EQ(p.from, Vec3(1, 2, 3));
  EXPECT_EQ(p.light_to_world.point(Vec3(0, 0, 0)), Vec3(0, 1, 0));
  EXPECT_EQ(s.lights[1].type, LightDesc::Type::Spot);
  EXPECT_EQ(s.lights[1].to, Vec3(0, -1, 0));
  EXPECT_FLOAT_EQ(s.lights[1].cone_angle, 20);
  EXPECT_FLOAT_EQ(s.lights[1].cone_delta, 2);
  EXPECT_EQ(s.lights[2].type, LightDesc::Type::Distant);
  EXPECT_NEAR(s.lights[2].spectrum.luminance(), 1.0f, 1e-4);
  EXPECT_EQ(s.lights[3].type, LightDesc::Type::Infinite);
  EXPECT_EQ(s.lights[3].filename, dir.path() + "/sky.exr");
  EXPECT_TRUE(has_warning(s, "test.pbrt:6:52: warning: \"power\" ignored"));
  EXPECT_TRUE(has_warning(s, "test.pbrt:7:1: warning: LightSource \"goniometric\" is not supported"));
}

TEST(ParserLights, AreaLightOnShapes) {
  SceneDesc s = parse_world(
      "AttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [4 5 6] \"float scale\" 2 "
      "\"bool twosided\" true\nShape \"sphere\"\nAttributeEnd\nShape \"sphere\"\n");
  ASSERT_TRUE(s.shapes[0].area_light.has_value());
  expect_rgb(s.shapes[0].area_light->L, RGB(4, 5, 6));
  EXPECT_FLOAT_EQ(s.shapes[0].area_light->scale, 2);
  EXPECT_TRUE(s.shapes[0].area_light->two_sided);
  EXPECT_FALSE(s.shapes[1].area_light.has_value());  // the attribute block ended it
}

TEST(ParserMedia, PresetsExplicitCoefficientsAndInterfaces) {
  SceneDesc s = parse_world(
      "MakeNamedMedium \"skin\" \"string type\" \"homogeneous\" \"string preset\" \"skin1\" \"float scale\" 0.1\n"
      "MakeNamedMedium \"milk\" \"string type\" \"homogeneous\" \"string name\" \"Wholemilk\"\n"
      "MakeNamedMedium \"fog\" \"string type\" \"homogeneous\" \"rgb sigma_a\" [0.1 0.2 0.3]\n"
      "  \"rgb sigma_s\" [1 2 3] \"float g\" 0.7\n"
      "MakeNamedMedium \"cloud\" \"string type\" \"cloud\"\n"
      "MediumInterface \"skin\" \"fog\"\nShape \"sphere\"\n"
      "MediumInterface \"cloud\"\nShape \"sphere\"\n"
      "MediumInterface \"milk\"\nShape \"sphere\"\n");
  ASSERT_EQ(s.media.size(), 4u);
  const MediumDesc& skin = s.media[0];
  EXPECT_EQ(skin.preset, "Skin1");
  // Jensen et al. 2001, Table 2, Skin1: sigma_s' = (0.74, 0.88, 1.01), sigma_a = (0.032, 0.17, 0.48) mm^-1.
  expect_rgb(skin.sigma_s, RGB(0.74f, 0.88f, 1.01f));
  expect_rgb(skin.sigma_a, RGB(0.032f, 0.17f, 0.48f));
  EXPECT_FLOAT_EQ(skin.g, 0);
  EXPECT_FLOAT_EQ(skin.scale, 0.1f);
  EXPECT_EQ(s.media[1].preset, "Wholemilk");
  expect_rgb(s.media[1].sigma_s, RGB(2.55f, 3.21f, 3.77f));
  expect_rgb(s.media[2].sigma_a, RGB(0.1f, 0.2f, 0.3f));
  expect_rgb(s.media[2].sigma_s, RGB(1, 2, 3));
  EXPECT_FLOAT_EQ(s.media[2].g, 0.7f);
  EXPECT_EQ(s.shapes[0].inside_medium, 0);
  EXPECT_EQ(s.shapes[0].outside_medium, 2);
  EXPECT_TRUE(s.shapes[0].has_medium_interface);
  EXPECT_EQ(s.shapes[1].inside_medium, 3);  // one name: inside and outside
  EXPECT_FALSE(s.shapes[1].has_medium_interface);
  EXPECT_EQ(s.shapes[2].inside_medium, 1);  // one name: inside and outside
  EXPECT_EQ(s.shapes[2].outside_medium, 1);
  EXPECT_FALSE(s.shapes[2].has_medium_interface);
}

// set_material_parameters: a material re-read with some parameters changed equals the
// material written that way in the scene.
TEST(ParserMaterialEdit, EqualsTheSceneWrittenWithTheChange) {
  const std::string before =
      "Texture \"t\" \"spectrum\" \"constant\" \"rgb value\" [0.2 0.4 0.6]\n"
      "MakeNamedMaterial \"skin\" \"string type\" \"subsurface\" \"rgb mfp\" [1 2 3] "
      "\"rgb reflectance\" [0.5 0.5 0.5] \"string method\" \"randomwalk\"\n"
      "NamedMaterial \"skin\"\nShape \"sphere\"\n";
  SceneDesc edited = parse_world(before);
  const auto warnings = set_material_parameters(edited, 0, "\"string method\" \"disk\" \"texture reflectance\" \"t\"");
  EXPECT_TRUE(warnings.empty());
  SceneDesc written = parse_world(
      "Texture \"t\" \"spectrum\" \"constant\" \"rgb value\" [0.2 0.4 0.6]\n"
      "MakeNamedMaterial \"skin\" \"string type\" \"subsurface\" \"rgb mfp\" [1 2 3] "
      "\"texture reflectance\" \"t\" \"string method\" \"disk\"\nNamedMaterial \"skin\"\nShape \"sphere\"\n");
  const SubsurfaceParams& a = edited.materials[0].subsurface;
  const SubsurfaceParams& b = written.materials[0].subsurface;
  EXPECT_EQ(edited.materials[0].name, "skin");
  EXPECT_EQ(a.method, SubsurfaceParams::Method::Disk);
  EXPECT_EQ(a.method, b.method);
  EXPECT_EQ(a.reflectance_texture, 0);
  EXPECT_EQ(a.reflectance_texture, b.reflectance_texture);
  ASSERT_TRUE(a.mfp && b.mfp);
  expect_rgb(*a.mfp, *b.mfp);
  EXPECT_EQ(edited.shapes[0].material, 0);
}

TEST(ParserMaterialEdit, ChangesTypeAndKeepsValuesExactly) {
  SceneDesc s = parse_world("Material \"diffuse\" \"rgb reflectance\" [0.1 0.123456789 0.3]\nShape \"sphere\"\n");
  set_material_parameters(s, 0, "\"float eta\" 1.4");  // unused by diffuse: warned
  expect_rgb(s.materials[0].reflectance.value, RGB(0.1f, 0.123456789f, 0.3f), 0);
  set_material_parameters(s, 0, "\"string type\" \"dielectric\" \"float eta\" 1.4 \"rgb reflectance\" [0 0 0]");
  EXPECT_EQ(s.materials[0].type, MaterialDesc::Type::Dielectric);
  EXPECT_FLOAT_EQ(s.materials[0].eta, 1.4f);
}

TEST(ParserMaterialEdit, BadTextIsAnErrorWithItsPositionAndChangesNothing) {
  SceneDesc s = parse_world("Material \"subsurface\" \"string method\" \"randomwalk\"\nShape \"sphere\"\n");
  try {
    set_material_parameters(s, 0, "\"string method\" \"nonsense\"", "<python>");
    FAIL() << "expected a SceneError";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("<python>:1:"), std::string::npos) << e.what();
  }
  EXPECT_EQ(s.materials[0].subsurface.method, SubsurfaceParams::Method::RandomWalk);
  EXPECT_THROW(set_material_parameters(s, 0, "\"string method\" \"disk\" 12"), SceneError);  // trailing junk
  EXPECT_THROW(set_material_parameters(s, 0, "\"texture reflectance\" \"nope\""), SceneError);
  EXPECT_THROW(set_material_parameters(s, 3, ""), std::out_of_range);
  const auto warnings = set_material_parameters(s, 0, "\"float nonsense\" 1");
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("nonsense"), std::string::npos) << warnings[0];
  EXPECT_TRUE(s.diagnostics.warnings.empty() || s.diagnostics.warnings.back().find("nonsense") == std::string::npos);
}

}  // namespace
}  // namespace dermis
