// The walk's strategies with one colour channel per walk at the camera's first entry
// (render/subsurface/walk_method.h, WalkStrategy::channel_per_walk): three exits, walk k
// drawn in channel k alone and counted three times; the same picture as the shared walks,
// with far less noise where the channels' extinction differs.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "dermis/render/integrator.h"
#include "dermis/render/scene_preparation.h"
#include "dermis/render/subsurface/subsurface_method.h"
#include "dermis/render/subsurface_pilot.h"
#include "dermis/scene/parser.h"
#include "support/pixel_statistics.h"

namespace dermis {
namespace {

// A milk-like sphere (extinction 1.5x apart from red to blue) under a uniform sky alone:
// the family's f02 (bench/vs_cycles), small.
std::string sky_sphere(const std::string& material_extra = "") {
  return R"(LookAt 0 -4 0  0 0 0  0 0 1
Camera "perspective" "float fov" 30
Film "rgb" "integer xresolution" 12 "integer yresolution" 12
Integrator "volpath" "integer maxdepth" 100000
WorldBegin
LightSource "infinite" "rgb L" [0.6 0.75 1]
Material "subsurface" "rgb reflectance" [0.95 0.93 0.88] "rgb mfp" [0.24 0.2 0.16] "float eta" 1.4)" +
         material_extra + R"(
Shape "sphere" "float radius" 1
)";
}

int strategy_index(bool channel_per_walk, float p_guided) {
  for (std::size_t v = 0; v < kWalkStrategies.size(); ++v)
    if (kWalkStrategies[v].channel_per_walk == channel_per_walk && kWalkStrategies[v].p_guided == p_guided &&
        (channel_per_walk || kWalkStrategies[v].channel_preference == 0.0f))
      return int(v);
  ADD_FAILURE() << "no such strategy";
  return 0;
}

testing::PixelStatistics render_with(const RenderScene& sc, int strategy, int spp, uint64_t seed) {
  const std::vector<int> strategies{strategy};
  PathStart start;
  start.subsurface_strategies = &strategies;
  return testing::pixel_statistics(sc, spp, seed, start);
}

// Per pixel of the sphere (brighter than the sky in red), the variance of one sample
// (R + G + B) from the standard errors of spp samples, for renders a and b; their means
// over the pixels and those means' standard errors (pixels are independent: from their
// spread).
struct Variances {
  double a, a_se, b, b_se;
};
Variances sphere_variances(const testing::PixelStatistics& a, const testing::PixelStatistics& b, int spp) {
  std::vector<double> va, vb;
  for (std::size_t p = 0; p < a.mean.size(); ++p) {
    if (!(a.mean[p][0] > 0.7f * 0.6f)) continue;  // the sky itself: 0.6 in red; the sphere brighter
    double x = 0, y = 0;
    for (int c = 0; c < 3; ++c) {
      x += spp * double(a.stderr_[p][c]) * a.stderr_[p][c];
      y += spp * double(b.stderr_[p][c]) * b.stderr_[p][c];
    }
    va.push_back(x), vb.push_back(y);
  }
  EXPECT_GE(va.size(), 40u);
  auto mean_and_se = [](const std::vector<double>& v) {
    double s = 0, s2 = 0;
    for (double x : v) s += x, s2 += x * x;
    const double n = double(v.size()), m = s / n;
    return std::pair{m, std::sqrt(std::max(0.0, s2 / n - m * m) / n)};
  };
  const auto [ma, sa] = mean_and_se(va);
  const auto [mb, sb] = mean_and_se(vb);
  return {ma, sa, mb, sb};
}

// Variance b below `share` of variance a by more than 4 standard errors.
void expect_less_noise(const Variances& v, double share) {
  EXPECT_GT(share * v.a - v.b, 4 * std::sqrt(share * share * v.a_se * v.a_se + v.b_se * v.b_se))
      << v.b << " vs " << share << " x " << v.a;
}

// The exits it asks for: a multiple of three of what the entry would take (the scene's
// subsurfacesamples through the diffuse boundary's exit lobe, one through the others),
// only for these strategies.
TEST(ChannelPerWalk, TakesAMultipleOfThreeExits) {
  Diagnostics diag;
  auto sc = build_render_scene(parse_scene_string(sky_sphere()), diag);
  const SubsurfaceMaterial& m = *sc->subsurface[0];
  ASSERT_TRUE(m.exits_through_lobe());
  EXPECT_EQ(m.strategy_count(), int(kWalkStrategies.size()));
  const int per_walk = strategy_index(true, 0.0f), shared = strategy_index(false, 0.0f);
  EXPECT_EQ(m.first_entry_exits(per_walk, 1), 3);
  EXPECT_EQ(m.first_entry_exits(per_walk, 2), 3);
  EXPECT_EQ(m.first_entry_exits(per_walk, 4), 6);
  EXPECT_EQ(m.first_entry_exits(shared, 2), 2);
  // The dielectric boundary: one exit per walk, or three.
  auto glass = build_render_scene(parse_scene_string(sky_sphere(R"( "string boundary" "dielectric")")), diag);
  const SubsurfaceMaterial& g = *glass->subsurface[0];
  EXPECT_FALSE(g.exits_through_lobe());
  EXPECT_EQ(g.strategy_count(), int(kWalkStrategies.size()));
  EXPECT_EQ(g.first_entry_exits(per_walk, 2), 3);
  EXPECT_EQ(g.first_entry_exits(shared, 2), 1);
}

// The same picture as the shared walks of the same guided share (region means within 4
// standard errors), and the mean per-pixel variance below what three shared walks would
// give by more than 4 standard errors: through the diffuse boundary the shared walks take
// the scene's 2 exits per entry (3 would give 2/3 of their variance), through the
// dielectric one 1 exit, each going on along its own refracted direction (3 would give
// 1/3). Measured (printed): 0.07x and 0.12x through the diffuse boundary, 0.06x on the
// family's f02; through the dielectric one far less. Walks whose channels were not
// separated (3 shared walks) fail the second check; channels not weighted 3x, or the other
// exits' ways on not followed, the first.
TEST(ChannelPerWalk, SamePictureLessNoiseWhereTheExtinctionDiffersByChannel) {
  Diagnostics diag;
  struct Case {
    const char* boundary;
    float p_guided;
    double more_walks;  // the variance 3 shared walks would give, of the shared walks'
  };
  for (const Case& k :
       {Case{"diffuse", 0.0f, 2.0 / 3.0}, Case{"diffuse", 0.5f, 2.0 / 3.0}, Case{"dielectric", 0.0f, 1.0 / 3.0}}) {
    SCOPED_TRACE(k.boundary);
    SCOPED_TRACE(k.p_guided);
    auto sc = build_render_scene(
        parse_scene_string(sky_sphere(std::string(" \"string boundary\" \"") + k.boundary + "\"")), diag);
    const float p_guided = k.p_guided;
    const auto shared = render_with(*sc, strategy_index(false, p_guided), 256, 11);
    const auto per_walk = render_with(*sc, strategy_index(true, p_guided), 256, 12);
    testing::expect_same_region_means(shared, per_walk, 3, 3);
    const Variances v = sphere_variances(shared, per_walk, 256);
    std::printf(
        "%s boundary, guided share %.1f: variance per sample %.4g (shared) vs %.4g (one channel per walk): "
        "%.3gx\n",
        k.boundary, double(p_guided), v.a, v.b, v.b / v.a);
    expect_less_noise(v, k.more_walks);
  }
}

// Where the shared walk is precise (grey extinction, the reflectance still coloured: its
// weights do not spread), the same picture, each guided share and both boundaries: region
// means within 4 standard errors, where those errors are small enough to see a bias of one
// per cent in blue (a weight of sqrt(albedo) per collision, about 0.5 % per collision in
// blue, reads 4-7 sigma off in several regions).
TEST(ChannelPerWalk, SamePictureAsThePreciseSharedWalk) {
  Diagnostics diag;
  for (const char* boundary : {"diffuse", "dielectric"})
    for (const float p_guided : {0.0f, 0.5f}) {
      SCOPED_TRACE(boundary);
      SCOPED_TRACE(p_guided);
      std::string scene = sky_sphere(std::string(" \"string boundary\" \"") + boundary + "\"");
      const std::string mfp = R"("rgb mfp" [0.24 0.2 0.16])";
      scene.replace(scene.find(mfp), mfp.size(), R"("rgb mfp" [0.2 0.2 0.2])");
      auto sc = build_render_scene(parse_scene_string(scene), diag);
      testing::expect_same_region_means(render_with(*sc, strategy_index(false, p_guided), 128, 31),
                                        render_with(*sc, strategy_index(true, p_guided), 128, 32), 3, 3);
    }
}

// The material's "bool channelperwalk" pins it (with the guided share, nothing is left
// for the pilot to choose); false keeps the shared walks in every strategy.
TEST(ChannelPerWalk, TheMaterialParameterPinsIt) {
  Diagnostics diag;
  auto pinned =
      build_render_scene(parse_scene_string(sky_sphere(R"( "bool channelperwalk" true "float guidedshare" 0)")), diag);
  const SubsurfaceMaterial& m = *pinned->subsurface[0];
  EXPECT_EQ(m.strategy_count(), 1);
  EXPECT_FALSE(subsurface_pilot_wanted(*pinned));
  EXPECT_TRUE(m.channel_per_walk(0));
  EXPECT_EQ(m.first_entry_exits(0, 2), 3);
  auto off = build_render_scene(parse_scene_string(sky_sphere(R"( "bool channelperwalk" false)")), diag);
  for (int v = 0; v < off->subsurface[0]->strategy_count(); ++v) EXPECT_FALSE(off->subsurface[0]->channel_per_walk(v));
  EXPECT_THROW(parse_scene_string(sky_sphere(R"( "bool channelperwalk" 1)")), SceneError);
  // Pinned, with the pilot's strategies out of the way (strategy 0 is the material's own):
  // the same picture as the shared classical walk, and less noise.
  auto shared =
      build_render_scene(parse_scene_string(sky_sphere(R"( "float guidedshare" 0 "float channelpreference" 0)")), diag);
  const auto a = render_with(*shared, 0, 256, 21);
  const auto b = render_with(*pinned, 0, 256, 22);
  testing::expect_same_region_means(a, b, 3, 3);
  expect_less_noise(sphere_variances(a, b, 256), 2.0 / 3.0);  // 3 shared walks would give 2/3
}

// The camera's first entry is the first subsurface entry of the camera's path through
// smooth glass or mirrors, not only its first hit: the same sphere behind a pane of glass
// gets one channel per walk too (before, its entry took one shared walk whatever the
// strategy: the same noise as the shared walks, which fails the second check). The same
// picture as the shared walks, and the noise below what three of them give.
// The sky-lit sphere behind a small pane of glass near the camera: it fills the view, and
// hides little of the sky from the sphere.
std::string sky_sphere_behind_glass() {
  return sky_sphere() + R"(Material "dielectric" "float eta" 1.5
Shape "trianglemesh" "point3 P" [-0.4 -3.6 -0.4  0.4 -3.6 -0.4  0.4 -3.6 0.4  -0.4 -3.6 0.4  -0.4 -3.5 -0.4  0.4 -3.5 -0.4  0.4 -3.5 0.4  -0.4 -3.5 0.4]
  "integer indices" [0 1 2  0 2 3   4 6 5  4 7 6   0 4 5  0 5 1   1 5 6  1 6 2   2 6 7  2 7 3   3 7 4  3 4 0]
)";
}

TEST(ChannelPerWalk, ServesTheSphereSeenThroughGlass) {
  Diagnostics diag;
  auto sc = build_render_scene(parse_scene_string(sky_sphere_behind_glass()), diag);
  const auto shared = render_with(*sc, strategy_index(false, 0.0f), 256, 41);
  const auto per_walk = render_with(*sc, strategy_index(true, 0.0f), 256, 42);
  testing::expect_same_region_means(shared, per_walk, 3, 3);
  const Variances v = sphere_variances(shared, per_walk, 256);
  std::printf("behind glass: variance per sample %.4g (shared) vs %.4g (one channel per walk): %.3gx\n", v.a, v.b,
              v.b / v.a);
  expect_less_noise(v, 2.0 / 3.0);
}

// The pilot's choices on a scene (seed 3, as for a render of 256 spp).
std::vector<SubsurfaceChoice> pilot_choices(const std::string& scene) {
  Diagnostics diag;
  auto sc = build_render_scene(parse_scene_string(scene), diag);
  SubsurfacePilotOptions o;
  o.seed = 3;
  o.spp = 256;
  o.bounds = PixelBounds{0, 0, sc->film.xres, sc->film.yres};
  o.full_width = sc->film.xres;
  return run_subsurface_pilot(*sc, o);
}

// On that sphere the pilot measures the difference and chooses one channel per walk.
TEST(ChannelPerWalk, ThePilotChoosesItOnTheSkyLitMilkSphere) {
  const auto choices = pilot_choices(sky_sphere());
  ASSERT_EQ(choices.size(), 1u);
  EXPECT_TRUE(kWalkStrategies[std::size_t(choices[0].strategy)].channel_per_walk) << choices[0].description;
  EXPECT_NE(choices[0].description.find("one colour channel per walk"), std::string::npos) << choices[0].description;
}

// The pilot finds the sphere behind the glass too (its probes follow the camera's path
// through smooth glass: before, it saw only the pane and chose nothing) and chooses one
// channel per walk there.
TEST(ChannelPerWalk, ThePilotChoosesItBehindGlass) {
  const auto choices = pilot_choices(sky_sphere_behind_glass());
  ASSERT_EQ(choices.size(), 1u);
  EXPECT_TRUE(kWalkStrategies[std::size_t(choices[0].strategy)].channel_per_walk) << choices[0].description;
}

}  // namespace
}  // namespace dermis
