// Directive-by-directive checks of the SceneDesc the parser produces.
#include "dermis/scene/parser.h"

#include <gtest/gtest.h>

#include <cmath>

#include "dermis/scene/scene_test_util.h"

namespace dermis {
namespace {

using test::expect_matrix_near;
using test::has_warning;
using test::parse_world;
using test::rows;

TEST(ParserTransforms, TranslateThenScaleComposeOnTheRight) {
  SceneDesc s = parse_world("Translate 1 2 3\nScale 2 4 8\nShape \"sphere\"");
  ASSERT_EQ(s.shapes.size(), 1u);
  expect_matrix_near(s.shapes[0].object_to_world.matrix(), rows({2, 0, 0, 1, 0, 4, 0, 2, 0, 0, 8, 3, 0, 0, 0, 1}));
  expect_matrix_near(s.shapes[0].object_to_world.inverse_matrix(),
                     rows({0.5, 0, 0, -0.5, 0, 0.25, 0, -0.5, 0, 0, 0.125, -0.375, 0, 0, 0, 1}));
}

TEST(ParserTransforms, RotateAboutZ) {
  SceneDesc s = parse_world("Rotate 90 0 0 1\nShape \"sphere\"");
  // Right-handed rotation by 90 degrees about +z: x -> y, y -> -x.
  expect_matrix_near(s.shapes[0].object_to_world.matrix(), rows({0, -1, 0, 0, 1, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}),
                     1e-12);
}

TEST(ParserTransforms, RotateAboutArbitraryAxisIsRodrigues) {
  // 120 degrees about (1,1,1) permutes the axes: x -> y -> z -> x.
  SceneDesc s = parse_world("Rotate 120 1 1 1\nShape \"sphere\"");
  expect_matrix_near(s.shapes[0].object_to_world.matrix(), rows({0, 0, 1, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0, 1}),
                     1e-12);
}

TEST(ParserTransforms, TransformIsTransposedOnInput) {
  SceneDesc s = parse_world("Transform [1 0 0 0  0 1 0 0  0 0 1 0  5 6 7 1]\nShape \"sphere\"");
  expect_matrix_near(s.shapes[0].object_to_world.matrix(), rows({1, 0, 0, 5, 0, 1, 0, 6, 0, 0, 1, 7, 0, 0, 0, 1}));
}

TEST(ParserTransforms, TransformReplacesAndConcatTransformMultiplies) {
  SceneDesc s = parse_world(
      "Translate 100 0 0\nTransform [2 0 0 0  0 2 0 0  0 0 2 0  0 0 0 1]\n"
      "ConcatTransform [1 0 0 0  0 1 0 0  0 0 1 0  1 2 3 1]\nShape \"sphere\"");
  // Scale(2) * Translate(1,2,3).
  expect_matrix_near(s.shapes[0].object_to_world.matrix(), rows({2, 0, 0, 2, 0, 2, 0, 4, 0, 0, 2, 6, 0, 0, 0, 1}));
}

TEST(ParserTransforms, IdentityResets) {
  SceneDesc s = parse_world("Translate 1 2 3\nIdentity\nShape \"sphere\"");
  EXPECT_TRUE(s.shapes[0].object_to_world.is_identity());
}

TEST(ParserTransforms, LookAtCameraToWorld) {
  // Eye at the origin looking down +x with +z up: camera x (right) = world +y,
  // camera y (up) = world +z, camera z (forward) = world +x.
  SceneDesc s = test::parse_text("LookAt 0 0 0  1 0 0  0 0 1\nCamera \"perspective\"\nWorldBegin\n");
  expect_matrix_near(s.camera.camera_to_world.matrix(), rows({0, 0, 1, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0, 1}), 1e-12);
}

TEST(ParserTransforms, LookAtWithOffsetEye) {
  SceneDesc s = test::parse_text("LookAt 1 2 3  1 2 8  0 1 0\nCamera \"perspective\"\nWorldBegin\n");
  expect_matrix_near(s.camera.camera_to_world.matrix(), rows({1, 0, 0, 1, 0, 1, 0, 2, 0, 0, 1, 3, 0, 0, 0, 1}), 1e-12);
}

TEST(ParserTransforms, CameraToWorldIsInverseOfCtm) {
  // pbrt: the CTM at Camera maps world to camera. Scale -1 1 1 flips x (the usual pbrt idiom).
  SceneDesc s = test::parse_text("Scale -1 1 1\nTranslate 0 0 5\nCamera \"perspective\"\nWorldBegin\n");
  expect_matrix_near(s.camera.camera_to_world.matrix(), rows({-1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, -5, 0, 0, 0, 1}));
}

TEST(ParserTransforms, CoordinateSystemsIncludingCamera) {
  SceneDesc s = test::parse_text(
      "Translate 0 0 4\nCamera \"perspective\"\nWorldBegin\n"
      "Translate 1 0 0\nCoordinateSystem \"mine\"\nIdentity\n"
      "CoordSysTransform \"mine\"\nShape \"sphere\"\n"
      "CoordSysTransform \"camera\"\nShape \"sphere\"\n"
      "CoordSysTransform \"world\"\nShape \"sphere\"\n");
  ASSERT_EQ(s.shapes.size(), 3u);
  expect_matrix_near(s.shapes[0].object_to_world.matrix(), rows({1, 0, 0, 1, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}));
  expect_matrix_near(s.shapes[1].object_to_world.matrix(), rows({1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, -4, 0, 0, 0, 1}));
  EXPECT_TRUE(s.shapes[2].object_to_world.is_identity());
}

TEST(ParserTransforms, WorldBeginResetsCtm) {
  SceneDesc s = test::parse_text("Translate 1 2 3\nWorldBegin\nShape \"sphere\"\nLightSource \"point\"\nWorldEnd\n");
  EXPECT_TRUE(s.shapes[0].object_to_world.is_identity());
  EXPECT_TRUE(s.diagnostics.warnings.empty());
}

TEST(ParserTransforms, MotionDirectivesWarn) {
  SceneDesc s = parse_world("ActiveTransform StartTime\nTranslate 1 0 0\nActiveTransform All\nTransformTimes 0 1\n");
  EXPECT_TRUE(has_warning(s, "test.pbrt:2:1: warning: ActiveTransform ignored"));
  EXPECT_TRUE(has_warning(s, "test.pbrt:5:1: warning: TransformTimes ignored"));
}

TEST(ParserBlocks, AttributeBlocksRestoreEverything) {
  SceneDesc s = parse_world(
      "MakeNamedMedium \"m\" \"string type\" \"homogeneous\"\n"
      "AttributeBegin\n Translate 1 0 0\n Material \"conductor\"\n AreaLightSource \"diffuse\"\n"
      " ReverseOrientation\n MediumInterface \"m\" \"\"\n Shape \"sphere\"\nAttributeEnd\n"
      "Shape \"sphere\"\n");
  ASSERT_EQ(s.shapes.size(), 2u);
  const ShapeDesc &in = s.shapes[0], &out = s.shapes[1];
  EXPECT_EQ(in.material, 0);
  EXPECT_TRUE(in.area_light.has_value());
  EXPECT_TRUE(in.reverse_orientation);
  EXPECT_EQ(in.inside_medium, 0);
  EXPECT_EQ(in.outside_medium, -1);
  EXPECT_TRUE(in.has_medium_interface);
  EXPECT_EQ(out.material, -1);
  EXPECT_FALSE(out.area_light.has_value());
  EXPECT_FALSE(out.reverse_orientation);
  EXPECT_FALSE(out.has_medium_interface);
  EXPECT_TRUE(out.object_to_world.is_identity());
}

TEST(ParserBlocks, TransformBlocksRestoreOnlyTheCtmAndWarn) {
  SceneDesc s =
      parse_world("TransformBegin\nTranslate 1 0 0\nMaterial \"conductor\"\nTransformEnd\nShape \"sphere\"\n");
  EXPECT_TRUE(s.shapes[0].object_to_world.is_identity());
  EXPECT_EQ(s.shapes[0].material, 0);
  EXPECT_TRUE(has_warning(s, "test.pbrt:2:1: warning: TransformBegin is deprecated"));
}

TEST(ParserBlocks, ReverseOrientationXorHandedness) {
  SceneDesc s = parse_world(
      "Shape \"sphere\"\n"
      "AttributeBegin ReverseOrientation Shape \"sphere\" AttributeEnd\n"
      "AttributeBegin Scale -1 1 1 Shape \"sphere\" AttributeEnd\n"
      "AttributeBegin Scale -1 1 1 ReverseOrientation Shape \"sphere\" AttributeEnd\n");
  ASSERT_EQ(s.shapes.size(), 4u);
  EXPECT_FALSE(s.shapes[0].reverse_orientation);
  EXPECT_TRUE(s.shapes[1].reverse_orientation);
  EXPECT_TRUE(s.shapes[2].reverse_orientation);
  EXPECT_FALSE(s.shapes[3].reverse_orientation);
}

// Both are what a file cut short looks like; pbrt-v4 refuses them too.
TEST(ParserBlocks, UnclosedAttributeBeginIsAnError) {
  try {
    parse_world("AttributeBegin\nShape \"sphere\"\n");
    FAIL() << "expected a SceneError";
  } catch (const SceneError& e) {
    EXPECT_STREQ(e.what(),
                 "test.pbrt:2:1: error: AttributeBegin has no matching AttributeEnd (is the file cut short?)");
  }
  EXPECT_NO_THROW(parse_world("AttributeBegin\nShape \"sphere\"\nAttributeEnd\n"));
}

TEST(ParserBlocks, ASceneWithoutWorldBeginIsAnError) {
  for (const std::string text : {"", "# only a comment\n", "Camera \"perspective\"\n"}) {
    try {
      test::parse_text(text);
      FAIL() << "expected a SceneError for '" << text << "'";
    } catch (const SceneError& e) {
      EXPECT_STREQ(e.what(),
                   "test.pbrt:1:1: error: the scene ends before WorldBegin: a scene describes its camera "
                   "and film, then WorldBegin, then its lights and shapes (is the file empty or cut short?)");
    }
  }
  EXPECT_NO_THROW(test::parse_text("WorldBegin\n"));
}

TEST(ParserOptions, CameraParameters) {
  SceneDesc s = test::parse_text(
      "Camera \"perspective\" \"float fov\" 45 \"float lensradius\" 0.1 \"float focaldistance\" 3\n"
      "  \"float screenwindow\" [-1 1 -0.5 0.5]\nWorldBegin\n");
  EXPECT_FLOAT_EQ(s.camera.fov, 45);
  EXPECT_FLOAT_EQ(s.camera.lens_radius, 0.1f);
  EXPECT_FLOAT_EQ(s.camera.focal_distance, 3);
  ASSERT_TRUE(s.camera.screen_window.has_value());
  EXPECT_FLOAT_EQ((*s.camera.screen_window)[1], 1);
  EXPECT_FLOAT_EQ((*s.camera.screen_window)[2], -0.5f);
  EXPECT_EQ(s.camera.loc.line, 1);
  EXPECT_EQ(s.camera.medium, -1);
}

TEST(ParserOptions, CameraDefaultsAndMedium) {
  SceneDesc s = test::parse_text(
      "MakeNamedMedium \"fog\" \"string type\" \"homogeneous\"\nMediumInterface \"\" \"fog\"\n"
      "Camera \"perspective\"\nWorldBegin\n");
  EXPECT_FLOAT_EQ(s.camera.fov, 90);
  EXPECT_FLOAT_EQ(s.camera.lens_radius, 0);
  EXPECT_FALSE(s.camera.screen_window.has_value());
  EXPECT_EQ(s.camera.medium, 0);  // the outside medium at Camera
}

TEST(ParserOptions, FilmFilterSamplerIntegrator) {
  SceneDesc s = test::parse_text(
      "Film \"rgb\" \"integer xresolution\" 320 \"integer yresolution\" 200 \"string filename\" \"out.exr\"\n"
      "PixelFilter \"box\" \"float xradius\" 0.75\n"
      "Sampler \"zsobol\" \"integer pixelsamples\" 64 \"integer seed\" 7\n"
      "Integrator \"path\" \"integer maxdepth\" 12\nWorldBegin\nLightSource \"point\"\n");
  EXPECT_EQ(s.film.xres, 320);
  EXPECT_EQ(s.film.yres, 200);
  EXPECT_EQ(s.film.filename, "out.exr");
  EXPECT_EQ(s.film.filter.type, FilterDesc::Type::Box);
  EXPECT_FLOAT_EQ(s.film.filter.radius.x, 0.75f);
  EXPECT_FLOAT_EQ(s.film.filter.radius.y, 0.5f);
  EXPECT_EQ(s.settings.spp, 64);
  EXPECT_EQ(s.settings.seed, 7);
  EXPECT_EQ(s.settings.integrator, "path");
  EXPECT_EQ(s.settings.max_depth, 12);
  EXPECT_EQ(s.settings.subsurface_samples, 2);  // the default
  EXPECT_TRUE(s.diagnostics.warnings.empty());
  EXPECT_EQ(test::parse_text("Integrator \"volpath\" \"integer subsurfacesamples\" 4\nWorldBegin\n")
                .settings.subsurface_samples,
            4);
  // An Integrator parameter's bad value: an error whose text contains `message`.
  auto expect_integrator_error = [](const std::string& parameter, const char* bad, const std::string& message) {
    try {
      test::parse_text("Integrator \"volpath\" " + parameter + " " + bad + "\nWorldBegin\n");
      ADD_FAILURE() << "no error for " << bad;
    } catch (const SceneError& e) {
      EXPECT_NE(std::string(e.what()).find(message), std::string::npos) << e.what();
    }
  };
  for (const char* bad : {"0", "65", "-1"})
    expect_integrator_error("\"integer subsurfacesamples\"", bad,
                            "test.pbrt:1:50: error: subsurfacesamples must lie in [1, 64], got " + std::string(bad));
  EXPECT_FLOAT_EQ(s.settings.split_threshold, 2);  // the default
  EXPECT_FLOAT_EQ(
      test::parse_text("Integrator \"volpath\" \"float splitthreshold\" 0\nWorldBegin\n").settings.split_threshold, 0);
  EXPECT_FLOAT_EQ(
      test::parse_text("Integrator \"volpath\" \"float splitthreshold\" 1.5\nWorldBegin\n").settings.split_threshold,
      1.5f);
  for (const char* bad : {"0.5", "-1", "0.999"})
    expect_integrator_error("\"float splitthreshold\"", bad,
                            "test.pbrt:1:45: error: splitthreshold must be 0 (no splitting) or a finite number of "
                            "at least 1, got ");
}

TEST(ParserOptions, SamplerNamesMapToTheNearestSampler) {
  EXPECT_EQ(test::parse_text("Sampler \"zsobol\"\nWorldBegin\n").settings.sampler, SamplerKind::Sobol);
  EXPECT_EQ(test::parse_text("Sampler \"paddedsobol\"\nWorldBegin\n").settings.sampler, SamplerKind::Sobol);
  SceneDesc ind = test::parse_text("Sampler \"independent\"\nWorldBegin\nLightSource \"point\"\n");
  EXPECT_EQ(ind.settings.sampler, SamplerKind::Independent);
  EXPECT_TRUE(ind.diagnostics.warnings.empty());
  SceneDesc halton = test::parse_text("Sampler \"halton\" \"integer pixelsamples\" 8\nWorldBegin\n");
  EXPECT_EQ(halton.settings.sampler, SamplerKind::Sobol);
  EXPECT_EQ(halton.settings.spp, 8);
  EXPECT_TRUE(has_warning(halton, "test.pbrt:1:9: warning: Sampler \"halton\" is not available; using \"sobol\""));
  SceneDesc digits = test::parse_text("Sampler \"sobol\" \"string randomization\" \"permutedigits\"\nWorldBegin\n");
  EXPECT_TRUE(has_warning(digits, "warning: Sampler \"randomization\" \"permutedigits\" is not available"));
}

// pbrt-v4's Film "sensor": "cie1931" is what Dermis records; a camera's sensor is one clear
// warning at the parameter (rendered as cie1931); a name pbrt-v4 does not know is an error.
TEST(ParserOptions, FilmSensor) {
  const std::string lit = "WorldBegin\nLightSource \"point\"\n";
  EXPECT_TRUE(test::parse_text("Film \"rgb\" \"string sensor\" \"cie1931\"\n" + lit).diagnostics.warnings.empty());
  SceneDesc canon = test::parse_text("Film \"rgb\" \"float iso\" 200 \"string sensor\" \"canon_eos_100d\"\n" + lit);
  ASSERT_EQ(canon.diagnostics.warnings.size(), 1u);
  EXPECT_TRUE(has_warning(canon,
                          "test.pbrt:1:28: warning: Film \"sensor\" \"canon_eos_100d\": camera sensor "
                          "responses are not modelled; rendered with the \"cie1931\" sensor"));
  EXPECT_FLOAT_EQ(canon.film.exposure_scale, 2);
  try {
    test::parse_text("Film \"rgb\" \"string sensor\" \"canon_eos_99d\"\n" + lit);
    ADD_FAILURE() << "no error";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("test.pbrt:1:28: error: unknown Film \"sensor\" \"canon_eos_99d\""),
              std::string::npos)
        << e.what();
  }
}

TEST(ParserOptions, GaussianFilterAndFallbacks) {
  SceneDesc s = test::parse_text(
      "Film \"gbuffer\"\nPixelFilter \"mitchell\" \"float sigma\" 0.7\nIntegrator \"bdpt\"\nWorldBegin\n");
  EXPECT_EQ(s.film.filter.type, FilterDesc::Type::Gaussian);
  EXPECT_FLOAT_EQ(s.film.filter.radius.x, 1.5f);
  EXPECT_FLOAT_EQ(s.film.filter.sigma, 0.7f);
  EXPECT_EQ(s.settings.integrator, "volpath");
  EXPECT_TRUE(has_warning(s, "test.pbrt:1:1: warning: Film \"gbuffer\""));
  EXPECT_TRUE(has_warning(s, "test.pbrt:2:1: warning: PixelFilter \"mitchell\""));
  EXPECT_TRUE(has_warning(s, "test.pbrt:3:1: warning: Integrator \"bdpt\""));
}

TEST(ParserWarnings, UnusedParameterNameFileLineCol) {
  SceneDesc s = parse_world("Shape \"sphere\" \"float radius\" 2 \"float bogus\" 1\n");
  EXPECT_TRUE(has_warning(s, "test.pbrt:2:33: warning: unused parameter \"float bogus\""));
  ASSERT_EQ(s.shapes.size(), 1u);
  EXPECT_FLOAT_EQ(s.shapes[0].radius, 2);
}

// Input quoted in a message is cut: a 100 kB identifier is not echoed whole.
TEST(ParserErrors, LongTokensAreNotEchoedWhole) {
  const std::string huge(100000, 'x');
  try {
    parse_world(huge + "\n");
    FAIL() << "expected a SceneError";
  } catch (const SceneError& e) {
    EXPECT_LT(std::string(e.what()).size(), 300u) << e.what();
    EXPECT_NE(std::string(e.what()).find("(100000 bytes in all)"), std::string::npos) << e.what();
  }
}

TEST(ParserWarnings, IgnoredDirectives) {
  SceneDesc s = test::parse_text(
      "ColorSpace \"aces2065-1\"\nOption \"bool wavefront\" true\nAccelerator \"bvh\"\nWorldBegin\n"
      "Attribute \"shape\" \"float radius\" 2\n");
  EXPECT_TRUE(has_warning(s, "test.pbrt:1:1: warning: ColorSpace"));
  EXPECT_TRUE(has_warning(s, "test.pbrt:2:1: warning: Option \"wavefront\" ignored"));
  EXPECT_TRUE(has_warning(s, "test.pbrt:3:1: warning: Accelerator ignored"));
  EXPECT_TRUE(has_warning(s, "test.pbrt:5:1: warning: Attribute \"shape\" ignored (parameters: radius)"));
}

// Not pbrt-v4's rule (the main file's directory), accepted with a warning at the name.
TEST(ParserInclude, BesideTheIncludingFileIsAFallbackWithAWarning) {
  test::TempDir dir;
  dir.write("sub/inner.pbrt", "Shape \"sphere\" \"float radius\" 7\n");
  dir.write("sub/outer.pbrt", "Translate 0 1 0\nInclude \"inner.pbrt\"\n");
  std::string main = dir.write("main.pbrt", "WorldBegin\nInclude \"sub/outer.pbrt\"\nImport \"sub/inner.pbrt\"\n");
  SceneDesc s = parse_scene_file(main);
  EXPECT_TRUE(has_warning(s, dir.path() + "/sub/outer.pbrt:2:9: warning: 'inner.pbrt' is not in the main scene file's "
                                          "directory"));
  // One cause, one warning: a chain of such Includes is warned about once.
  for (int i = 0; i < 5; ++i)
    dir.write("c/inc/" + std::to_string(i) + ".pbrt", "Include \"" + std::to_string(i + 1) + ".pbrt\"\n");
  dir.write("c/inc/5.pbrt", "Shape \"sphere\"\n");
  SceneDesc c =
      parse_scene_file(dir.write("c/main.pbrt", "WorldBegin\nLightSource \"point\"\nInclude \"inc/0.pbrt\"\n"));
  EXPECT_EQ(c.shapes.size(), 1u);
  EXPECT_EQ(c.diagnostics.warnings.size(), 1u);
  ASSERT_EQ(s.shapes.size(), 2u);
  EXPECT_FLOAT_EQ(s.shapes[0].radius, 7);
  // Include shares the graphics state: the Translate of outer.pbrt still applies.
  expect_matrix_near(s.shapes[1].object_to_world.matrix(), rows({1, 0, 0, 0, 0, 1, 0, 1, 0, 0, 1, 0, 0, 0, 0, 1}));
  EXPECT_EQ(s.shapes[0].loc.line, 1);
  EXPECT_NE(s.shapes[0].loc.file.find("inner.pbrt"), std::string::npos);
  EXPECT_EQ(s.base_directory, dir.path());
}

TEST(ParserInclude, GzipIncludeParsesLikeThePlainOne) {
  test::TempDir dir;
  const std::string inner =
      "Translate 0 1 0\n# a comment\nShape \"sphere\" \"float radius\" 7\nAttribute \"shape\" \"float radius\" 2\n";
  dir.write("plain.pbrt", inner);
  dir.write("sub/inner.pbrt.gz", test::gzip(inner));
  SceneDesc plain = parse_scene_file(dir.write("a.pbrt", "WorldBegin\nInclude \"plain.pbrt\"\n"));
  SceneDesc gz = parse_scene_file(dir.write("b.pbrt", "WorldBegin\nImport \"sub/inner.pbrt.gz\"\n"));
  ASSERT_EQ(gz.shapes.size(), 1u);
  ASSERT_EQ(plain.shapes.size(), 1u);
  EXPECT_FLOAT_EQ(gz.shapes[0].radius, 7);
  expect_matrix_near(gz.shapes[0].object_to_world.matrix(), plain.shapes[0].object_to_world.matrix());
  // Locations point into the decompressed text of the included file.
  EXPECT_EQ(gz.shapes[0].loc.file, dir.path() + "/sub/inner.pbrt.gz");
  EXPECT_EQ(gz.shapes[0].loc.line, 3);
  EXPECT_EQ(gz.shapes[0].loc.column, 1);
  EXPECT_TRUE(has_warning(gz, dir.path() + "/sub/inner.pbrt.gz:4:1: warning:"));
  // The main scene file may be compressed too.
  SceneDesc main_gz = parse_scene_file(dir.write("c.pbrt.gz", test::gzip("WorldBegin\nInclude \"plain.pbrt\"\n")));
  ASSERT_EQ(main_gz.shapes.size(), 1u);
  EXPECT_FLOAT_EQ(main_gz.shapes[0].radius, 7);
}

TEST(ParserInclude, ErrorsInAGzipIncludePointIntoItsText) {
  test::TempDir dir;
  dir.write("inner.pbrt.gz", test::gzip("Shape \"sphere\"\n\n  Shape \"sphere\" \"float radius\" [ 1\n"));
  try {
    parse_scene_file(dir.write("main.pbrt", "WorldBegin\nInclude \"inner.pbrt.gz\"\n"));
    FAIL() << "no error";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.loc().file, dir.path() + "/inner.pbrt.gz") << e.what();
    EXPECT_EQ(e.loc().line, 3) << e.what();
    EXPECT_GE(e.loc().column, 3) << e.what();
  }
}

TEST(ParserInclude, StringBaseDirectory) {
  test::TempDir dir;
  dir.write("a.pbrt", "Shape \"sphere\"\n");
  SceneDesc s = parse_scene_string("WorldBegin Include \"a.pbrt\"", "s", dir.path());
  EXPECT_EQ(s.shapes.size(), 1u);
}

TEST(ParserObjects, InstancesComposeWithTheShapeCtm) {
  SceneDesc s = parse_world(
      "ObjectInstance \"early\"\n"  // pbrt-v4 resolves names after parsing
      "Translate 0 0 9\n"
      "ObjectBegin \"early\"\n Translate 1 0 0\n Shape \"sphere\"\nObjectEnd\n"
      "Shape \"sphere\"\n"
      "Translate 0 5 0\nObjectInstance \"early\"\n");
  ASSERT_EQ(s.objects.size(), 1u);
  ASSERT_EQ(s.objects[0].shapes.size(), 1u);
  EXPECT_EQ(s.objects[0].name, "early");
  // The shape keeps its full CTM at definition time (pbrt-v4's convention).
  expect_matrix_near(s.objects[0].shapes[0].object_to_world.matrix(),
                     rows({1, 0, 0, 1, 0, 1, 0, 0, 0, 0, 1, 9, 0, 0, 0, 1}));
  // ObjectBegin/End is an attribute block: the Translate inside does not leak.
  ASSERT_EQ(s.shapes.size(), 1u);
  expect_matrix_near(s.shapes[0].object_to_world.matrix(), rows({1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 9, 0, 0, 0, 1}));
  ASSERT_EQ(s.instances.size(), 2u);
  EXPECT_EQ(s.instances[0].object, 0);
  EXPECT_TRUE(s.instances[0].object_to_world.is_identity());
  EXPECT_EQ(s.instances[1].object, 0);
  expect_matrix_near(s.instances[1].object_to_world.matrix(), rows({1, 0, 0, 0, 0, 1, 0, 5, 0, 0, 1, 9, 0, 0, 0, 1}));
}

TEST(ParserObjects, AreaLightsAndMediaInsideObjectsWarn) {
  SceneDesc s = parse_world(
      "MakeNamedMedium \"m\" \"string type\" \"homogeneous\"\n"
      "AreaLightSource \"diffuse\"\nObjectBegin \"o\"\nMediumInterface \"m\"\nShape \"sphere\"\nObjectEnd\n");
  EXPECT_FALSE(s.objects[0].shapes[0].area_light.has_value());
  EXPECT_EQ(s.objects[0].shapes[0].inside_medium, -1);
  EXPECT_TRUE(has_warning(s, "test.pbrt:5:1: warning: MediumInterface inside ObjectBegin"));
  EXPECT_TRUE(has_warning(s, "test.pbrt:6:1: warning: area lights are not supported on instanced shapes"));
}

}  // namespace
}  // namespace dermis

namespace dermis {
namespace {

// A chain of 100 Includes stops at the depth limit with a message, not a stack overflow.
TEST(ParserInclude, ChainsDeeperThanTheLimitAreAnError) {
  test::TempDir dir;
  for (int i = 0; i < 100; ++i)
    dir.write("f" + std::to_string(i) + ".pbrt", "Include \"f" + std::to_string(i + 1) + ".pbrt\"\n");
  dir.write("f100.pbrt", "WorldBegin\n");
  try {
    parse_scene_file(dir.path() + "/f0.pbrt");
    ADD_FAILURE() << "no error";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("Include nested more than 64 files deep"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace dermis

namespace dermis {
namespace {

// pbrt-v4 (ParseFiles sets the search directory once, from the main file): a relative path
// in an included file names a file in the main file's directory, for Include, Import and
// file parameters alike.
TEST(ParserInclude, RelativePathsResolveAgainstTheMainFilesDirectory) {
  test::TempDir dir;
  dir.write("inner.pbrt", "Shape \"sphere\" \"float radius\" 1\n");
  dir.write("sub/inner.pbrt", "Shape \"sphere\" \"float radius\" 2\n");
  dir.write("sky.exr", "x");
  dir.write("sub/sky.exr", "x");
  dir.write(
      "sub/outer.pbrt",
      "Include \"inner.pbrt\"\nImport \"inner.pbrt\"\nLightSource \"infinite\" \"string filename\" \"sky.exr\"\n");
  SceneDesc s = parse_scene_file(dir.write("main.pbrt", "WorldBegin\nInclude \"sub/outer.pbrt\"\n"));
  ASSERT_EQ(s.shapes.size(), 2u);
  EXPECT_FLOAT_EQ(s.shapes[0].radius, 1);
  EXPECT_FLOAT_EQ(s.shapes[1].radius, 1);
  EXPECT_EQ(s.lights[0].filename, dir.path() + "/sky.exr");
  EXPECT_TRUE(s.diagnostics.warnings.empty()) << s.diagnostics.warnings.front();
}

// smoke-plume (pbrt-v4-scenes) ends an included file in the middle of MakeNamedMedium's
// parameters and continues them after the Include: one token stream, as pbrt-v4 reads it.
TEST(ParserInclude, AParameterListContinuesAfterTheIncludedFile) {
  test::TempDir dir;
  dir.write("geometry/density.pbrt",
            "MakeNamedMedium \"smoke\" \"string type\" \"homogeneous\"\n  \"float scale\" 2\n");
  SceneDesc s = parse_scene_file(dir.write("main.pbrt",
                                           "WorldBegin\nAttributeBegin\nInclude \"geometry/density.pbrt\"\n"
                                           "\t\"rgb sigma_a\" [1 2 3]\n\t\"rgb sigma_s\" [4 5 6]\n"
                                           "MediumInterface \"smoke\" \"\"\nMaterial \"interface\"\nShape \"sphere\"\n"
                                           "AttributeEnd\nLightSource \"point\"\n"));
  ASSERT_EQ(s.media.size(), 1u);
  EXPECT_FLOAT_EQ(s.media[0].sigma_a[2], 3);
  EXPECT_FLOAT_EQ(s.media[0].sigma_s[0], 4);
  EXPECT_FLOAT_EQ(s.media[0].scale, 2);
  ASSERT_EQ(s.shapes.size(), 1u);
  EXPECT_EQ(s.shapes[0].inside_medium, 0);
  EXPECT_TRUE(s.diagnostics.warnings.empty()) << s.diagnostics.warnings.front();
  // Errors in the continued list point into the file that holds them.
  dir.write("bad.pbrt", "WorldBegin\nInclude \"geometry/density.pbrt\"\n  \"rgb sigma_a\" [1 2]\n");
  try {
    parse_scene_file(dir.path() + "/bad.pbrt");
    ADD_FAILURE() << "no error";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.loc().file, dir.path() + "/bad.pbrt") << e.what();
    EXPECT_EQ(e.loc().line, 3) << e.what();
  }
}

TEST(ParserInclude, ImportKeepsItsGraphicsStateToItself) {
  test::TempDir dir;
  dir.write("part.pbrt", "Translate 0 0 5\nShape \"sphere\"\n");
  SceneDesc s = parse_scene_file(dir.write("main.pbrt", "WorldBegin\nImport \"part.pbrt\"\nShape \"sphere\"\n"));
  ASSERT_EQ(s.shapes.size(), 2u);
  EXPECT_FALSE(s.shapes[0].object_to_world.is_identity());
  EXPECT_TRUE(s.shapes[1].object_to_world.is_identity());
  dir.write("open.pbrt", "AttributeBegin\n");
  EXPECT_THROW(parse_scene_file(dir.write("m2.pbrt", "WorldBegin\nImport \"open.pbrt\"\n")), SceneError);
  EXPECT_THROW(parse_scene_file(dir.write("m3.pbrt", "Import \"part.pbrt\"\n")), SceneError);  // world only
}

// pbrt-v4 looks media up when it builds the scene: a MediumInterface may come first.
TEST(ParserMedia, MediumInterfaceMayNameAMediumDefinedLater) {
  SceneDesc s = test::parse_text(
      "MediumInterface \"\" \"air\"\nCamera \"perspective\"\nWorldBegin\n"
      "MediumInterface \"fog\" \"air\"\nShape \"sphere\"\nLightSource \"point\"\n"
      "MakeNamedMedium \"fog\" \"string type\" \"homogeneous\"\n"
      "MakeNamedMedium \"air\" \"string type\" \"homogeneous\" \"rgb sigma_a\" [0 0 0]\n");
  ASSERT_EQ(s.media.size(), 2u);
  EXPECT_EQ(s.shapes[0].inside_medium, 0);
  EXPECT_EQ(s.shapes[0].outside_medium, 1);
  EXPECT_TRUE(s.shapes[0].has_medium_interface);
  EXPECT_EQ(s.camera.medium, 1);
  EXPECT_EQ(s.lights[0].medium, 1);
  // A name never defined: an error where it is used.
  try {
    parse_world(
        "Shape \"sphere\"\nMediumInterface \"fog\" \"smog\"\nShape \"sphere\"\n"
        "MakeNamedMedium \"fog\" \"string type\" \"homogeneous\"\n");
    ADD_FAILURE() << "no error";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.loc().line, 3) << e.what();
    EXPECT_EQ(e.loc().column, 23) << e.what();
    EXPECT_NE(std::string(e.what()).find("unknown medium \"smog\""), std::string::npos) << e.what();
  }
  // Named but never used by anything: nothing to resolve, as in pbrt-v4.
  EXPECT_NO_THROW(parse_world("MediumInterface \"nowhere\"\n"));
}

TEST(ParserMessages, ASceneWithoutLightsWarnsOnce) {
  SceneDesc dark = parse_world("Shape \"sphere\"\nShape \"sphere\"\n");
  int count = 0;
  for (const std::string& w : dark.diagnostics.warnings) count += w.find("no lights") != std::string::npos;
  EXPECT_EQ(count, 1);
  EXPECT_TRUE(has_warning(dark, "test.pbrt:1:1: warning: the scene has no lights"));
  EXPECT_FALSE(has_warning(parse_world("AreaLightSource \"diffuse\"\nShape \"sphere\"\n"), "no lights"));
  EXPECT_FALSE(has_warning(parse_world("LightSource \"distant\"\n"), "no lights"));
}

// Every parameter nobody read is warned at its place, for unsupported materials and shapes
// too; the unsupported thing itself once.
TEST(ParserMessages, ParametersOfUnsupportedMaterialsAndShapesAreWarned) {
  // pbrt-v4's "measured" is rendered diffuse: its own parameters are warned unused, the
  // reflectance its stand-in reads is not. (hair and curve, once here, are now read: their
  // tests are ParserHair.* and ParserCurve.*; a curve's unknown parameter is still warned.)
  SceneDesc s = parse_world(
      "LightSource \"point\"\n"
      "Material \"measured\" \"string filename\" \"x.bsdf\" \"rgb reflectance\" [0.2 0.2 0.2]\n"
      "Shape \"curve\" \"point3 P\" [0 0 0 1 0 0 2 0 0 3 0 0] \"point3 p1\" [0 0 0]\n");
  EXPECT_TRUE(has_warning(s, "test.pbrt:3:1: warning: unsupported material \"measured\""));
  EXPECT_TRUE(has_warning(s, "test.pbrt:3:21: warning: unused parameter \"string filename\""));
  EXPECT_FALSE(has_warning(s, "\"rgb reflectance\""));  // read by the diffuse stand-in
  EXPECT_TRUE(has_warning(s, "test.pbrt:4:52: warning: unused parameter \"point3 p1\""));
  EXPECT_EQ(s.diagnostics.warnings.size(), 3u);
}

}  // namespace
}  // namespace dermis
