#include "dermis/render/renderer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <optional>

#include "dermis/render/scene_preparation.h"
#include "support/pixel_statistics.h"
#include "support/small_scene.h"

namespace dermis {
namespace {

using testing::small_scene;

// The default sampler (Owen-scrambled Sobol') changes the noise, never the mean: every
// path-tracer branch (medium in glass, floor, spot and environment light), 8
// randomisations of 16 Sobol' samples against 128 independent samples, in 12 regions of
// 10 x 10 pixels, within 4 standard errors.
TEST(Renderer, SobolSamplerGivesTheMeanOfIndependentSampling) {
  Diagnostics diag;
  auto sc = build_render_scene(small_scene(), diag);
  auto sobol = testing::replicated_pixel_statistics(*sc, SamplerKind::Sobol, 16, 8, 50);
  auto indep = testing::pixel_statistics(*sc, 128, 51);
  testing::expect_same_region_means(sobol, indep, 10, 10);
}

// Splitting the camera's first hit (glass here) changes the noise, not the mean: the
// same scene with and without it, 128 independent samples each, 12 regions, within 4σ.
TEST(Renderer, SplittingTheFirstHitKeepsTheMean) {
  Diagnostics diag;
  auto sc = build_render_scene(small_scene(), diag);
  auto split = testing::pixel_statistics(*sc, 128, 60);
  sc->switches.split_first_hit = false;
  auto chosen = testing::pixel_statistics(*sc, 128, 61);
  testing::expect_same_region_means(split, chosen, 10, 10);
}

TEST(Renderer, SameSeedSameImageWhateverTheThreadCount) {
  Diagnostics diag;
  auto sc = build_render_scene(small_scene(), diag);
  RenderOptions o;
  o.spp = 6;
  o.seed = 42;
  o.threads = 1;
  RenderResult a = render_image(*sc, o);
  o.threads = 2;
  RenderResult b = render_image(*sc, o);
  ASSERT_EQ(a.rgb.size(), b.rgb.size());
  EXPECT_EQ(0, std::memcmp(a.rgb.data(), b.rgb.data(), a.rgb.size() * sizeof(float)));
  EXPECT_EQ(a.min_spp, 6u);
  EXPECT_EQ(a.max_spp, 6u);
  o.seed = 43;
  RenderResult c = render_image(*sc, o);
  EXPECT_NE(0, std::memcmp(a.rgb.data(), c.rgb.data(), a.rgb.size() * sizeof(float)));
}

// pbrt-v4's "cropwindow": only those pixels are rendered and written, each exactly as in
// the full image; "iso" scales the pixel values by iso / 100.
TEST(Renderer, CropWindowIsThatPartOfTheFullImageAndIsoScales) {
  Diagnostics diag;
  SceneDesc d = small_scene();
  RenderOptions o;
  o.spp = 2;
  o.seed = 3;
  RenderResult full = render_image(*build_render_scene(d, diag), o);
  d.film.crop = {0.3f, 0.8f, 0.15f, 0.7f};
  d.film.exposure_scale = 4;  // iso 400
  RenderResult crop = render_image(*build_render_scene(d, diag), o);
  // pbrt-v4's bounds: ceil(40 * 0.3) = 12 .. ceil(40 * 0.8) = 32, ceil(30 * 0.15) = 5 .. ceil(30 * 0.7) = 21.
  ASSERT_EQ(crop.width, 20);
  ASSERT_EQ(crop.height, 16);
  for (int y = 0; y < crop.height; ++y)
    for (int x = 0; x < crop.width; ++x)
      for (int c = 0; c < 3; ++c)
        ASSERT_EQ(crop.rgb[3 * (y * crop.width + x) + c], 4 * full.rgb[3 * ((y + 5) * 40 + x + 12) + c]);
}

TEST(Renderer, NonFiniteSamplesAreCountedAndNeverReachTheFilm) {
  SceneDesc d = small_scene();
  d.lights[0].spectrum = RGB(std::numeric_limits<float>::quiet_NaN());
  Diagnostics diag;
  auto sc = build_render_scene(d, diag);
  RenderOptions o;
  o.spp = 2;
  RenderResult r = render_image(*sc, o);
  EXPECT_GT(r.nonfinite, 0u);
  for (float v : r.rgb) EXPECT_TRUE(std::isfinite(v));
}

TEST(Renderer, CancelStopsEarlyWithAConsistentImage) {
  Diagnostics diag;
  auto sc = build_render_scene(small_scene(), diag);
  std::atomic<bool> cancel{true};
  RenderOptions o;
  o.spp = 64;
  o.cancel = &cancel;
  RenderResult r = render_image(*sc, o);
  EXPECT_TRUE(r.interrupted);
  EXPECT_EQ(r.max_spp, 0u);
  for (float v : r.rgb) EXPECT_EQ(v, 0.0f);
}

// A time limit spent before the first pass (a slow pilot, a loaded machine) still gives
// every pixel one sample, and then stops: an image with unrendered tiles is no picture.
TEST(Renderer, TimeLimitStopsOnlyOnceEveryPixelHasASample) {
  Diagnostics diag;
  auto sc = build_render_scene(small_scene(), diag);
  RenderOptions o;
  o.spp = 64;
  o.threads = 2;
  o.time_limit = 1e-9;
  RenderResult r = render_image(*sc, o);
  EXPECT_TRUE(r.time_limited);
  EXPECT_EQ(r.min_spp, 1u);
  EXPECT_EQ(r.max_spp, 1u);  // the second pass renders no tile
}

// A render continued from a saved film is bit-identical to one never stopped: from the
// state at the end of a shorter render (resumed to more samples), and from a film
// interrupted mid-pass, whose tiles hold different numbers of samples.
TEST(Renderer, ResumingFromAFilmIsBitIdenticalToNeverStopping) {
  Diagnostics diag;
  auto sc = build_render_scene(small_scene(), diag);
  RenderOptions o;
  o.spp = 6;
  o.seed = 11;
  o.threads = 2;
  const RenderResult whole = render_image(*sc, o);

  std::optional<Film> saved;
  RenderOptions first = o;
  first.spp = 2;
  first.checkpoint = [&](const Film& f) { saved = f; };
  render_image(*sc, first);
  ASSERT_TRUE(saved);
  RenderOptions rest = o;
  rest.resume = &*saved;
  const RenderResult resumed = render_image(*sc, rest);
  EXPECT_EQ(resumed.rgb, whole.rgb);
  EXPECT_EQ(resumed.samples, whole.samples);

  // Interrupted in the third pass: a 40x30 film has 3 x 2 tiles; passes of 1, 1 and 2
  // samples; on one thread the cancel set by the 15th tile leaves 3 tiles at 4 samples
  // and 3 at 2.
  std::atomic<bool> cancel{false};
  std::atomic<int> tiles{0};
  RenderOptions stopped = o;
  stopped.threads = 1;
  stopped.cancel = &cancel;
  stopped.progress = [&](int64_t) {
    if (++tiles == 15) cancel = true;
  };
  saved.reset();
  stopped.checkpoint = [&](const Film& f) { saved = f; };
  const RenderResult part = render_image(*sc, stopped);
  ASSERT_TRUE(part.interrupted && saved);
  EXPECT_EQ(part.min_spp, 2u);
  EXPECT_EQ(part.max_spp, 4u);
  rest.resume = &*saved;
  const RenderResult resumed2 = render_image(*sc, rest);
  EXPECT_EQ(resumed2.rgb, whole.rgb);
}

}  // namespace
}  // namespace dermis
