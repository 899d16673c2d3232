#include "dermis/scene/subsurface_params.h"

#include <gtest/gtest.h>

#include <cstring>

#include "dermis/render/renderer.h"
#include "dermis/render/scene_preparation.h"
#include "dermis/scene/parser.h"

namespace dermis {
namespace {

const char* kHeader = R"(LookAt 0 0 -4  0 0 0  0 1 0
Camera "perspective" "float fov" 30
Film "rgb" "integer xresolution" 16 "integer yresolution" 12
Integrator "volpath" "integer maxdepth" 200
WorldBegin
LightSource "infinite" "rgb L" [0.5 0.6 0.7]
LightSource "point" "rgb I" [3 3 3] "point3 from" [1 2 -3]
)";

SubsurfaceParams params_of(const std::string& material_line) {
  SceneDesc d = parse_scene_string(std::string(kHeader) + material_line + "\nShape \"sphere\"\n");
  return d.materials.at(0).subsurface;
}

TEST(SubsurfaceParams, ReadsCoefficientsScaleAndDermisOptions) {
  SubsurfaceParams p = params_of(
      "Material \"subsurface\" \"rgb sigma_a\" [1 2 3] \"rgb sigma_s\" [4 5 6] \"float scale\" 2 \"float eta\" 1.4 "
      "\"float g\" 0.3 \"string method\" \"volumetric\" \"string profile\" \"dipole\"");
  ASSERT_TRUE(p.sigma_a && p.sigma_s);
  EXPECT_EQ(*p.sigma_a, RGB(2, 4, 6));
  EXPECT_EQ(*p.sigma_s, RGB(8, 10, 12));
  EXPECT_FLOAT_EQ(p.eta, 1.4f);
  EXPECT_FLOAT_EQ(p.g, 0.3f);
  EXPECT_EQ(p.method, SubsurfaceParams::Method::Volumetric);
  EXPECT_EQ(p.profile, SubsurfaceParams::Profile::Dipole);
  EXPECT_FALSE(p.backward_guiding);  // the default
  EXPECT_TRUE(params_of("Material \"subsurface\" \"bool backwardguiding\" true").backward_guiding);
}

TEST(SubsurfaceParams, RoughnessAsPbrtV4) {
  SubsurfaceParams p = params_of(
      "Material \"subsurface\" \"float roughness\" 0.2 \"float vroughness\" 0.05 "
      "\"bool remaproughness\" false");
  EXPECT_FLOAT_EQ(p.uroughness, 0.2f);  // roughness sets both, vroughness overrides one
  EXPECT_FLOAT_EQ(p.vroughness, 0.05f);
  EXPECT_FALSE(p.remap_roughness);
  EXPECT_TRUE(params_of("Material \"subsurface\"").remap_roughness);
  EXPECT_THROW(params_of("Material \"subsurface\" \"float roughness\" -0.1"), SceneError);
}

// A float texture for "roughness" (both axes); uroughness / vroughness cannot be
// textured (warned), nor can the point cloud take one (warned).
TEST(SubsurfaceParams, TexturedRoughness) {
  auto scene = [](const std::string& material) {
    return parse_scene_string(std::string(kHeader) + "Texture \"r\" \"float\" \"constant\" \"float value\" 0.3\n" +
                              "Texture \"c\" \"spectrum\" \"constant\" \"rgb value\" [0.3 0.3 0.3]\n" + material +
                              "\nShape \"sphere\"\n");
  };
  auto warned = [](const SceneDesc& d, const std::string& what) {
    for (const std::string& w : d.diagnostics.warnings)
      if (w.find(what) != std::string::npos) return true;
    return false;
  };
  const SceneDesc d = scene("Material \"subsurface\" \"texture roughness\" \"r\"");
  const SubsurfaceParams& p = d.materials.at(0).subsurface;
  EXPECT_EQ(p.roughness_texture, 0);
  EXPECT_EQ(p.uroughness, 0.0f);
  EXPECT_FALSE(warned(d, "roughness"));
  const SceneDesc u = scene("Material \"subsurface\" \"texture uroughness\" \"r\"");
  EXPECT_EQ(u.materials.at(0).subsurface.roughness_texture, -1);
  EXPECT_TRUE(warned(u, "textured \"uroughness\" is not supported"));
  const SceneDesc both = scene("Material \"subsurface\" \"texture roughness\" \"r\" \"float vroughness\" 0.1");
  EXPECT_TRUE(warned(both, "ignored beside a textured \"roughness\""));
  EXPECT_EQ(both.materials.at(0).subsurface.vroughness, 0.0f);
  const SceneDesc cloud = scene("Material \"subsurface\" \"texture roughness\" \"r\" \"string method\" \"pointcloud\"");
  EXPECT_EQ(cloud.materials.at(0).subsurface.roughness_texture, -1);
  EXPECT_TRUE(warned(cloud, "not supported by the \"pointcloud\" method"));
  // A spectrum texture where a float one is needed: an error at the value.
  try {
    scene("Material \"subsurface\" \"texture roughness\" \"c\"");
    ADD_FAILURE() << "no error";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("unknown float texture \"c\""), std::string::npos) << e.what();
  }
}

TEST(SubsurfaceParams, PresetNameUsesJensenTableTimesScale) {
  SubsurfaceParams p = params_of("Material \"subsurface\" \"string name\" \"Skin1\" \"float scale\" 0.5");
  ASSERT_TRUE(p.sigma_a);
  // Jensen et al. 2001, Table 2, Skin1: sigma_s' = (0.74, 0.88, 1.01), sigma_a = (0.032, 0.17, 0.48) per mm.
  EXPECT_NEAR((*p.sigma_s)[0], 0.37f, 1e-6);
  EXPECT_NEAR((*p.sigma_a)[2], 0.24f, 1e-6);
}

// pbrt-v4 multiplies mfp by scale as it does the coefficients (materials.h, GetBSSRDF).
TEST(SubsurfaceParams, ScaleMultipliesMfpAsInPbrtV4) {
  SubsurfaceParams p =
      params_of("Material \"subsurface\" \"rgb reflectance\" [0.8 0.5 0.2] \"rgb mfp\" [1 2 4] \"float scale\" 2");
  ASSERT_TRUE(p.reflectance && p.mfp);
  EXPECT_EQ(*p.mfp, RGB(2, 4, 8));
}

TEST(SubsurfaceParams, BadInputIsAnErrorAtItsLocation) {
  auto expect_error = [](const std::string& line, const std::string& what) {
    try {
      params_of(line);
      ADD_FAILURE() << "no error for: " << line;
    } catch (const SceneError& e) {
      EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
      EXPECT_EQ(e.loc().line, 8) << e.what();  // the Material line, after the 7-line header
    }
  };
  expect_error("Material \"subsurface\" \"string method\" \"magic\"", "unknown subsurface method \"magic\"");
  expect_error("Material \"subsurface\" \"string method\" \"disk\" \"float normalaxis\" 1",
               "\"normalaxis\" must be in (0, 1)");
  expect_error("Material \"subsurface\" \"string profile\" \"gauss\"", "unknown profile");
  expect_error("Material \"subsurface\" \"string name\" \"Skin9\"", "unknown subsurface preset");
  expect_error("Material \"subsurface\" \"rgb reflectance\" [0.5 0.5 0.5]", "needs \"mfp\"");
  expect_error("Material \"subsurface\" \"rgb reflectance\" [1.5 0.5 0.5] \"rgb mfp\" [1 1 1]", "in [0, 1]");
  expect_error("Material \"subsurface\" \"rgb sigma_a\" [-1 0 0]", "non-negative");
  expect_error("Material \"subsurface\" \"float eta\" 0.5", "eta");
  expect_error("Material \"subsurface\" \"string name\" \"Skin1\" \"rgb sigma_a\" [1 1 1]", "either");
  expect_error("Material \"subsurface\" \"bool backwardguiding\" [true false]", "\"backwardguiding\" must be one bool");
  expect_error("Material \"subsurface\" \"float illuminationerror\" -0.1", "\"illuminationerror\" must be in [0, 1]");
  expect_error("Material \"subsurface\" \"float illuminationerror\" 2", "\"illuminationerror\" must be in [0, 1]");
  expect_error("Material \"subsurface\" \"string entry\" \"cosine\"",
               "\"entry\" must be \"refracted\" or \"lambertian\"");
  expect_error("Material \"subsurface\" \"string entry\" \"lambertian\" \"string boundary\" \"dielectric\"",
               "\"entry\" \"lambertian\" needs \"boundary\" \"diffuse\"");
}

// The walk's entry: refracted (the default) or a diffuse transmission with the `diffuse`
// boundary; another method ignores it, with a warning.
// The walk's boundary follows the parametrisation unless "boundary" is given: the
// coefficients (or a named medium, or none: pbrt-v4's milk) describe a physical object,
// rendered behind its dielectric; reflectance + mfp, the artist's, keeps `diffuse`.
TEST(SubsurfaceParams, DefaultBoundaryFollowsTheParametrisation) {
  using B = SubsurfaceParams::Boundary;
  EXPECT_EQ(params_of("Material \"subsurface\" \"rgb sigma_a\" [1 2 3] \"rgb sigma_s\" [4 5 6]").boundary,
            B::Dielectric);
  EXPECT_EQ(params_of("Material \"subsurface\" \"string name\" \"Skin1\"").boundary, B::Dielectric);
  EXPECT_EQ(params_of("Material \"subsurface\"").boundary, B::Dielectric);
  EXPECT_EQ(params_of("Material \"subsurface\" \"rgb reflectance\" [0.5 0.5 0.5] \"rgb mfp\" [1 1 1]").boundary,
            B::Diffuse);
  // Given, it is kept either way.
  EXPECT_EQ(params_of("Material \"subsurface\" \"string name\" \"Skin1\" \"string boundary\" \"diffuse\"").boundary,
            B::Diffuse);
  EXPECT_EQ(params_of("Material \"subsurface\" \"rgb reflectance\" [0.5 0.5 0.5] \"rgb mfp\" [1 1 1] "
                      "\"string boundary\" \"dielectric\"")
                .boundary,
            B::Dielectric);
  // "entry" "lambertian" is the diffuse boundary's own option: it keeps that boundary.
  EXPECT_EQ(params_of("Material \"subsurface\" \"string name\" \"Skin1\" \"string entry\" \"lambertian\"").boundary,
            B::Diffuse);
}

TEST(SubsurfaceParams, LambertianEntry) {
  EXPECT_FALSE(params_of("Material \"subsurface\"").lambertian_entry);
  EXPECT_FALSE(params_of("Material \"subsurface\" \"string entry\" \"refracted\"").lambertian_entry);
  EXPECT_TRUE(params_of("Material \"subsurface\" \"string entry\" \"lambertian\"").lambertian_entry);
  const SceneDesc disk = parse_scene_string(std::string(kHeader) +
                                            "Material \"subsurface\" \"string entry\" \"lambertian\" "
                                            "\"string method\" \"disk\"\nShape \"sphere\"\n");
  EXPECT_FALSE(disk.materials.at(0).subsurface.lambertian_entry);
  ASSERT_EQ(disk.diagnostics.warnings.size(), 1u);
  EXPECT_NE(disk.diagnostics.warnings[0].find("\"entry\" applies to the random walk only"), std::string::npos)
      << disk.diagnostics.warnings[0];
}

// The disk's probability of probing along the normal: unset, the pilot chooses (0.75 by
// default); given, in (0, 1) (else an error at its location: above); another method
// ignores it, with a warning.
TEST(SubsurfaceParams, NormalAxis) {
  const SubsurfaceParams unset = params_of("Material \"subsurface\" \"string method\" \"disk\"");
  EXPECT_FALSE(unset.normal_axis_given);
  EXPECT_EQ(unset.normal_axis, 0.75f);
  const SubsurfaceParams given =
      params_of("Material \"subsurface\" \"string method\" \"disk\" \"float normalaxis\" 0.9");
  EXPECT_TRUE(given.normal_axis_given);
  EXPECT_EQ(given.normal_axis, 0.9f);
  const SceneDesc walk =
      parse_scene_string(std::string(kHeader) + "Material \"subsurface\" \"float normalaxis\" 0.5\nShape \"sphere\"\n");
  EXPECT_FALSE(walk.materials.at(0).subsurface.normal_axis_given);
  ASSERT_EQ(walk.diagnostics.warnings.size(), 1u);
  EXPECT_NE(walk.diagnostics.warnings[0].find("\"normalaxis\" applies to the disk only; ignored by \"randomwalk\""),
            std::string::npos)
      << walk.diagnostics.warnings[0];
}

TEST(SubsurfaceVolumetric, IsExactlyAMediumInsideADielectric) {
  // The brute-force reference method builds the same scene as writing the medium by hand:
  // the images are bit-identical for the same seed.
  std::string a = std::string(kHeader) +
                  "Material \"subsurface\" \"rgb sigma_a\" [0.1 0.2 0.4] \"rgb sigma_s\" [2 3 4] \"float eta\" 1.4 "
                  "\"float g\" 0.2 \"string method\" \"volumetric\"\nShape \"sphere\"\n";
  std::string b = std::string(kHeader) +
                  "MakeNamedMedium \"m\" \"string type\" \"homogeneous\" \"rgb sigma_a\" [0.1 0.2 0.4] "
                  "\"rgb sigma_s\" [2 3 4] \"float g\" 0.2\nMediumInterface \"m\" \"\"\n"
                  "Material \"dielectric\" \"float eta\" 1.4\nShape \"sphere\"\n";
  RenderOptions o;
  o.spp = 4;
  o.seed = 5;
  Diagnostics diag;
  auto sa = build_render_scene(parse_scene_string(a), diag);
  auto sb = build_render_scene(parse_scene_string(b), diag);
  RenderResult ra = render_image(*sa, o), rb = render_image(*sb, o);
  ASSERT_EQ(ra.rgb.size(), rb.rgb.size());
  EXPECT_EQ(0, std::memcmp(ra.rgb.data(), rb.rgb.data(), ra.rgb.size() * sizeof(float)));
  float sum = 0;
  for (float v : ra.rgb) sum += v;
  EXPECT_GT(sum, 0);
}

}  // namespace
}  // namespace dermis

#include <fstream>
#include <sstream>

namespace dermis {
namespace {

// Every example in docs/materials.md parses and builds (the docs cannot drift from the code).
TEST(SubsurfaceDocs, EveryExampleInMaterialsMdBuilds) {
  std::ifstream in(std::string(DERMIS_SOURCE_DIR) + "/docs/materials.md");
  ASSERT_TRUE(in) << "docs/materials.md";
  std::string line, block;
  std::vector<std::string> examples;
  bool in_examples = false;
  while (std::getline(in, line)) {
    if (line.rfind("## Examples", 0) == 0) in_examples = true;
    if (!in_examples) continue;
    if (line.rfind("Material ", 0) == 0) {
      if (!block.empty()) examples.push_back(block);
      block = line + "\n";
    } else if (!block.empty() && line.rfind("    ", 0) == 0) {
      block += line + "\n";
    } else if (!block.empty()) {
      examples.push_back(block);
      block.clear();
    }
  }
  if (!block.empty()) examples.push_back(block);
  ASSERT_GE(examples.size(), 5u);
  for (const std::string& m : examples) {
    SCOPED_TRACE(m);
    Diagnostics diag;
    auto sc = build_render_scene(parse_scene_string(std::string(kHeader) + m + "Shape \"sphere\"\n"), diag);
    EXPECT_TRUE(diag.warnings.empty()) << diag.warnings.front();
  }
}

}  // namespace
}  // namespace dermis

namespace dermis {
namespace {

// docs/materials.md documents every parameter the reader knows (the table is the one
// place they are listed), and every name in the table is one the reader accepts.
TEST(SubsurfaceDocs, MaterialsMdDocumentsEveryParameter) {
  std::ifstream in(std::string(DERMIS_SOURCE_DIR) + "/docs/materials.md");
  ASSERT_TRUE(in) << "docs/materials.md";
  std::stringstream text;
  text << in.rdbuf();
  const std::string docs = text.str();
  for (const SubsurfaceParameter& p : subsurface_parameters()) {
    EXPECT_NE(docs.find(std::string(" ") + p.name + "\""), std::string::npos)
        << "docs/materials.md does not mention \"" << p.type << " " << p.name << "\"";
    // Accepted without an "unused parameter" warning.
    // The documented default as the value (rgb: a valid albedo).
    const std::string t(p.type);
    const std::string value = t.rfind("rgb", 0) == 0                          ? "[0.5 0.5 0.5]"
                              : t == "float" || t == "integer" || t == "bool" ? std::string(p.default_value)
                                                                              : "";
    if (value.empty()) continue;  // strings need a valid name: read by the tests above
    const std::string type = std::string(p.type).substr(0, std::string(p.type).find(' '));
    // reflectance and mfp come together.
    const std::string partner = std::string(p.name) == "reflectance" ? " \"rgb mfp\" [1 1 1]"
                                : std::string(p.name) == "mfp"       ? " \"rgb reflectance\" [0.5 0.5 0.5]"
                                                                     : "";
    SceneDesc d = parse_scene_string(std::string(kHeader) + "Material \"subsurface\" \"" + type + " " + p.name + "\" " +
                                     value + partner + "\nShape \"sphere\"\n");
    for (const std::string& w : d.diagnostics.warnings)
      EXPECT_EQ(w.find("unused parameter"), std::string::npos) << p.name << ": " << w;
  }
}

}  // namespace
}  // namespace dermis
