// The point-cloud method in the renderer: the flat-slab invariant within a stated
// tolerance (the cloud is an approximation by design: finite point density, octree
// criterion, equal area shares), with and without the local disk; save and load.
#include "dermis/render/point_cloud_prepass.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "dermis/materials/fresnel.h"
#include "dermis/render/scene_assembly.h"
#include "dermis/render/scene_preparation.h"
#include "dermis/scene/parser.h"
#include "support/pixel_statistics.h"

namespace dermis {
namespace {

std::string slab(bool local_disk) {
  return std::string(R"(LookAt 0 0 50  0 0 0  0 1 0
Camera "perspective" "float fov" 2
Film "rgb" "integer xresolution" 3 "integer yresolution" 3
Integrator "volpath" "integer maxdepth" 20
WorldBegin
LightSource "infinite" "rgb L" [1 1 1]
Material "subsurface" "rgb reflectance" [0.6 0.4 0.2] "rgb mfp" [1 1 1] "float eta" 1.33
  "string method" "pointcloud" "integer irradiancesamples" 4 "bool localdisk" )") +
         (local_disk ? "true" : "false") + R"(
Shape "trianglemesh" "point3 P" [-60 -60 -30  60 -60 -30  60 60 -30  -60 60 -30
                                  -60 -60 0  60 -60 0  60 60 0  -60 60 0]
  "integer indices" [0 2 1  0 3 2   4 5 6  4 6 7   0 1 5  0 5 4   1 2 6  1 6 5   2 3 7  2 7 6   3 0 4  3 4 7]
)";
}

// The image mean, per channel, of a surface of eta 1.33 seen at normal incidence under a
// uniform white sky: the Fresnel reflection plus the transmitted share of the profile's
// albedo, F + (1 - F) A. Stated tolerance: 3% of the albedo term (the library measured a
// -1% bias of the equal-area shares on planes) plus 4 standard errors of the render.
void expect_fresnel_plus_albedo(const RenderScene& sc) {
  const sss::ProfileRGB& profile = std::get<PointCloudMethod>(sc.subsurface[0]->method).profile();
  const float F = fresnel_dielectric(1.0f, 1.33f);
  auto st = testing::pixel_statistics(sc, 64, 5);
  for (int c = 0; c < 3; ++c) {
    const double expected = F + (1 - F) * profile.channel[c].albedo();
    double mean = 0, var = 0;
    for (std::size_t p = 0; p < st.mean.size(); ++p) {
      mean += st.mean[p][c] / st.mean.size();
      var += st.stderr_[p][c] * st.stderr_[p][c] / double(st.mean.size() * st.mean.size());
    }
    std::printf("channel %d: %.5f vs %.5f (%+.2f%%)\n", c, mean, expected, 100 * (mean / expected - 1));
    EXPECT_NEAR(mean, expected, 0.03 * (1 - F) * profile.channel[c].albedo() + 4 * std::sqrt(var)) << "channel " << c;
  }
}

// Also with the count chosen from the illumination (local disk, no --points): the slab
// under the uniform sky takes the 1024-point pilot (TheCountFollowsTheIllumination), a
// spacing of ~6 mfp, which the local disk keeps within the same tolerance.
TEST(PointCloudRender, FlatSlabReturnsFresnelPlusAlbedo) {
  for (int variant : {0, 1, 2}) {
    const bool local_disk = variant != 1;
    SCOPED_TRACE(variant == 0   ? "local disk"
                 : variant == 1 ? "plain octree"
                                : "local disk, count from the illumination");
    Diagnostics diag;
    PointCloudOptions o;
    o.points = variant == 2 ? 0 : 30000;  // ~0.8 mfp spacing on the top face
    auto sc = assemble_scene(parse_scene_string(slab(local_disk)), diag);
    PreparationOptions prep;
    prep.point_clouds = o;
    ASSERT_EQ(prepare_scene(*sc, prep).point_clouds.clouds, 1u);
    expect_fresnel_plus_albedo(*sc);
  }
}

// The same invariant on an analytic sphere 20 mean free paths in radius, seen at its
// centre. The points are placed on a tessellation of the sphere and must be moved onto
// the sphere the renderer traces: left on the facets (inside the sphere by up to their
// sagitta), their irradiance rays started inside the object, the sphere blocked them,
// and the cloud read 29% dark in red. Tolerance as above, with 30000 points (0.4 mfp
// apart; `disk` renders this sphere within 0.2% of the plane's value, so its curvature is
// not what the tolerance covers).
TEST(PointCloudRender, SphereUnderAUniformSkyReturnsFresnelPlusAlbedo) {
  Diagnostics diag;
  auto sc = assemble_scene(parse_scene_string(R"(LookAt 0 0 150  0 0 0  0 1 0
Camera "perspective" "float fov" 1
Film "rgb" "integer xresolution" 3 "integer yresolution" 3
Integrator "volpath" "integer maxdepth" 20
WorldBegin
LightSource "infinite" "rgb L" [1 1 1]
Material "subsurface" "rgb reflectance" [0.6 0.4 0.2] "rgb mfp" [1 1 1] "float eta" 1.33
  "string method" "pointcloud" "integer irradiancesamples" 4
Shape "sphere" "float radius" 20
)"),
                           diag);
  PreparationOptions prep;
  prep.point_clouds.points = 30000;
  ASSERT_EQ(prepare_scene(*sc, prep).point_clouds.clouds, 1u);
  expect_fresnel_plus_albedo(*sc);
}

TEST(PointCloudRender, SavedCloudLoadsAndRendersTheSame) {
  const std::string path = (std::filesystem::temp_directory_path() / "dermis_cloud_test.bin").string();
  Diagnostics diag;
  PointCloudOptions save;
  save.points = 2000;
  save.save_path = path;
  auto a = assemble_scene(parse_scene_string(slab(true)), diag);
  PreparationOptions prep;
  prep.point_clouds = save;
  EXPECT_GT(prepare_scene(*a, prep).point_clouds.file_bytes, 0u);
  PointCloudOptions load;
  load.load_path = path;
  auto b = build_render_scene(parse_scene_string(slab(true)), diag, load);
  auto sa = testing::pixel_statistics(*a, 8, 9), sb = testing::pixel_statistics(*b, 8, 9);
  for (std::size_t p = 0; p < sa.mean.size(); ++p) EXPECT_EQ(sa.mean[p], sb.mean[p]);
  std::filesystem::remove(path);
  PointCloudOptions missing;
  missing.load_path = path;
  EXPECT_THROW(build_render_scene(parse_scene_string(slab(true)), diag, missing), std::runtime_error);
}

// Asked to read or write a cloud for a scene that has none: a warning for each option, nothing read.
TEST(PointCloudRender, CloudFilesForASceneWithoutCloudsAreWarnedAbout) {
  Diagnostics diag;
  auto sc = assemble_scene(parse_scene_string("WorldBegin\nLightSource \"infinite\"\n"
                                              "Material \"subsurface\" \"string method\" \"disk\"\nShape \"sphere\"\n"),
                           diag);
  PreparationOptions prep;
  prep.point_clouds.load_path = "/nonexistent/cloud.bin";
  prep.point_clouds.save_path = "saved.bin";
  const PreparationReport r = prepare_scene(*sc, prep);
  EXPECT_EQ(r.point_clouds.clouds, 0u);
  ASSERT_EQ(r.point_clouds.warnings.size(), 2u);
  EXPECT_EQ(r.point_clouds.warnings[0],
            "warning: --load-pointcloud /nonexistent/cloud.bin: the scene has no object "
            "whose subsurface method is \"pointcloud\"; no point cloud was read");
  EXPECT_EQ(r.point_clouds.warnings[1],
            "warning: --save-pointcloud saved.bin: the scene has no object whose "
            "subsurface method is \"pointcloud\"; no point cloud was written");
  EXPECT_FALSE(std::filesystem::exists("saved.bin"));
}

// Without the refinement ("illuminationerror" 0) the density asks for area * pointdensity
// / mfp^2 points: the slab (area ~4.3e4, mfp 1) at density 1 asks for ~4.3e4; a
// "maxpoints" budget of 2000 caps it, with a warning that gives both spacings; within the
// budget there is no warning.
PreparationReport prepared(std::string text, const std::string& extra) {
  const std::string samples = "\"integer irradiancesamples\" 4";
  text.replace(text.find(samples), samples.size(), extra);
  Diagnostics diag;
  auto sc = assemble_scene(parse_scene_string(text), diag);
  return prepare_scene(*sc, {});
}
TEST(PointCloudRender, TheCloudIsCappedAtItsBudgetWithAWarning) {
  auto points_with = [](const std::string& extra, std::vector<std::string>* warnings) {
    const PreparationReport r =
        prepared(slab(true), "\"integer irradiancesamples\" 1 \"float illuminationerror\" 0 " + extra);
    *warnings = r.point_clouds.warnings;
    return r.point_clouds.points;
  };
  std::vector<std::string> warnings;
  EXPECT_EQ(points_with("\"integer maxpoints\" 2000", &warnings), 2000u);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(
      warnings[0].find("<string>:7:1: warning: point cloud of object 1: \"pointdensity\" 1 asks for 4.32e+04 points"),
      std::string::npos)
      << warnings[0];
  EXPECT_NE(warnings[0].find("budget of 2000"), std::string::npos) << warnings[0];
  EXPECT_EQ(points_with("\"integer maxpoints\" 2000 \"float pointdensity\" 0.04", &warnings), 1728u);  // 0.04 * 43200
  EXPECT_TRUE(warnings.empty());
}

// With the local disk the count follows the illumination (seed 001): under a uniform sky
// a convex slab receives the same E everywhere, and the pilot (1024 points, for a cap of
// the density's 43200) already represents it; a spot light's sharp-edged disk on the top
// face does not, and the cloud grows to the profile's density (the cap; a note, no
// warning) or, with a smaller budget, stops at the budget with a warning.
std::string spot_slab() {
  std::string text = slab(true);
  const std::string sky = "LightSource \"infinite\" \"rgb L\" [1 1 1]";
  text.replace(text.find(sky), sky.size(),
               "LightSource \"spot\" \"point3 from\" [0 0 40] \"point3 to\" [0 0 0] \"float coneangle\" 20 "
               "\"float conedeltaangle\" 1 \"rgb I\" [2000 2000 2000]");
  return text;
}
TEST(PointCloudRender, TheCountFollowsTheIllumination) {
  const PreparationReport sky = prepared(slab(true), "\"integer irradiancesamples\" 8");
  EXPECT_EQ(sky.point_clouds.points, 1024u);
  EXPECT_TRUE(sky.point_clouds.warnings.empty());
  ASSERT_EQ(sky.point_clouds.notes.size(), 1u);
  EXPECT_NE(sky.point_clouds.notes[0].find("point cloud of object 1: 1024 points represent the illumination to"),
            std::string::npos)
      << sky.point_clouds.notes[0];

  const PreparationReport spot = prepared(spot_slab(), "\"integer irradiancesamples\" 2");
  EXPECT_EQ(spot.point_clouds.points, 43200u);
  EXPECT_TRUE(spot.point_clouds.warnings.empty());
  ASSERT_EQ(spot.point_clouds.notes.size(), 1u);
  EXPECT_NE(spot.point_clouds.notes[0].find("by round: 1024 points: "), std::string::npos)
      << spot.point_clouds.notes[0];

  const PreparationReport budget = prepared(spot_slab(), "\"integer irradiancesamples\" 2 \"integer maxpoints\" 3000");
  EXPECT_EQ(budget.point_clouds.points, 3000u);
  ASSERT_EQ(budget.point_clouds.warnings.size(), 1u);
  EXPECT_NE(budget.point_clouds.warnings[0].find("<string>:7:1: warning: point cloud of object 1: 3000 points"),
            std::string::npos)
      << budget.point_clouds.warnings[0];
  EXPECT_NE(budget.point_clouds.warnings[0].find("coarser than the illumination needs"), std::string::npos);
  EXPECT_TRUE(budget.point_clouds.notes.empty());
}

// The blue-noise placement (the first, single-threaded part of the pre-pass) shows its own
// progress, and a cancel (Ctrl-C) stops it there: no irradiance pass is started.
TEST(PointCloudRender, PlacingThePointsShowsProgressAndStopsOnCancel) {
  std::string text = slab(true);
  const std::string samples = "\"integer irradiancesamples\" 4";
  text.replace(text.find(samples), samples.size(),
               "\"integer irradiancesamples\" 1 \"integer maxpoints\" 20000 \"float illuminationerror\" 0");
  Diagnostics diag;
  auto sc = assemble_scene(parse_scene_string(text), diag);
  prepare_scene(*sc, {});
  ::testing::internal::CaptureStderr();
  build_point_clouds(*sc, {}, Progress::Style::kLines, nullptr, nullptr);
  const std::string shown = ::testing::internal::GetCapturedStderr();
  EXPECT_NE(shown.find("Point cloud 1: placing 20000 points"), std::string::npos) << shown;
  EXPECT_NE(shown.find("Point cloud 1 (20000 points)"), std::string::npos) << shown;

  const std::atomic<bool> cancel{true};
  ::testing::internal::CaptureStderr();
  EXPECT_THROW(build_point_clouds(*sc, {}, Progress::Style::kLines, &cancel, nullptr), Interrupted);
  const std::string stopped = ::testing::internal::GetCapturedStderr();
  EXPECT_EQ(stopped.find("Point cloud 1 (20000 points)"), std::string::npos) << stopped;
}

}  // namespace
}  // namespace dermis
