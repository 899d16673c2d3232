#include "dermis/render/adaptive_sampling.h"

#include <gtest/gtest.h>

#include <atomic>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <optional>

#include "dermis/core/sampler.h"
#include "dermis/render/renderer.h"
#include "dermis/render/scene_preparation.h"
#include "support/pixel_statistics.h"
#include "support/small_scene.h"

namespace dermis {
namespace {

// Per-pixel means and standard errors (per channel) from a film's sums and squares.
testing::PixelStatistics statistics_of(const Film& film) {
  testing::PixelStatistics st;
  st.width = film.width;
  st.height = film.height;
  st.mean.resize(film.pixel_count());
  st.stderr_.resize(film.pixel_count());
  for (std::size_t p = 0; p < film.pixel_count(); ++p) {
    const double n = film.samples[p];
    for (int c = 0; c < 3; ++c) {
      const double m = film.sum[3 * p + c] / n;
      const double var = std::max(0.0, film.sum_sq[3 * p + c] / n - m * m) * n / (n - 1);
      st.mean[p][c] = float(m);
      st.stderr_[p][c] = float(std::sqrt(var / n));
    }
  }
  return st;
}

TEST(AdaptiveSampling, ErrorIsTheStandardErrorOverTheRootOfTheValue) {
  Film film(4, 1);
  // Pixel 0: samples 1, 3 in every channel: mean 2, variance 2, standard error 1.
  for (int c = 0; c < 3; ++c) film.sum[c] = 4, film.sum_sq[c] = 10;
  film.samples[0] = 2;
  EXPECT_NEAR(pixel_noise_error(film, 0, 1), 1 / std::sqrt(2.0), 1e-7);
  EXPECT_NEAR(pixel_noise_error(film, 0, 0.5), 0.5, 1e-7);           // at exposure 1/2 the value is 1: relative error
  EXPECT_NEAR(pixel_noise_error(film, 0, 4), std::sqrt(2.0), 1e-6);  // the error as written
  // Pixel 1: one sample: unknown.
  film.sum[3] = 1, film.sum_sq[3] = 1, film.samples[1] = 1;
  EXPECT_EQ(pixel_noise_error(film, 1, 1), std::numeric_limits<float>::infinity());
  // Pixel 2: 8 equal samples (a background): no error, and none for a black pixel (3).
  for (int c = 0; c < 3; ++c) film.sum[6 + c] = 8 * 0.25, film.sum_sq[6 + c] = 8 * 0.0625;
  film.samples[2] = 8, film.samples[3] = 8;
  EXPECT_EQ(pixel_noise_error(film, 2, 1), 0.0f);
  EXPECT_EQ(pixel_noise_error(film, 3, 1), 0.0f);
  // A near-black pixel is measured against the floor: samples 0 and 2e-4 in red only
  // (value 1e-4 / 3).
  film.sum[9] = 2e-4, film.sum_sq[9] = 4e-8;
  film.samples[3] = 2;
  const double se_red = 1e-4, rms = se_red / std::sqrt(3.0);
  EXPECT_NEAR(pixel_noise_error(film, 3, 1), rms / std::sqrt(kErrorValueFloor), 1e-6);
}

TEST(AdaptiveSampling, NeighbourhoodIsTheThreeByThreeMaximum) {
  // 4 x 3 map, one large value at (0, 0) and one at (3, 2).
  const std::vector<float> e = {5, 0, 0, 0,  //
                                0, 0, 0, 0,  //
                                0, 0, 0, 7};
  std::vector<float> m(e.size());
  neighbourhood_max(e, 4, 3, m);
  const std::vector<float> want = {5, 5, 0, 0,  //
                                   5, 5, 7, 7,  //
                                   0, 0, 7, 7};
  EXPECT_EQ(m, want);
}

TEST(AdaptiveSampling, PassesKeepCountsInBlocksOfTheSampler) {
  EXPECT_EQ(default_min_spp(4), 4);
  EXPECT_EQ(default_min_spp(256), 16);
  EXPECT_EQ(default_min_spp(1024), 32);
  EXPECT_EQ(default_min_spp(4096), 64);
  // From 16: +16 up to 128, then +32 up to 256, then +64 ...; never past spp.
  uint32_t n = 16;
  std::vector<uint32_t> seen;
  while (n < 400) seen.push_back(n = next_adaptive_count(n, 400));
  const std::vector<uint32_t> want = {32, 48, 64, 80, 96, 112, 128, 160, 192, 224, 256, 320, 384, 400};
  EXPECT_EQ(seen, want);
}

// Each pass of a pixel takes an aligned block of 2^k samples of its Owen-scrambled Sobol'
// sequence, so whatever count a pixel stops at, its samples are whole (0,k,2)-nets in the
// camera's two dimensions: in every block and every split of the square into 2^k equal
// rectangles (2^j x 2^(k-j)), one sample per rectangle.
TEST(AdaptiveSampling, EveryPassIsAStratifiedBlockOfThePixelsSequence) {
  int blocks = 0;
  for (uint64_t pixel : {3ull, 4242ull}) {
    uint32_t n = uint32_t(default_min_spp(1024));
    while (n < 1024) {
      const uint32_t next = next_adaptive_count(n, 1024), size = next - n;
      ASSERT_EQ(size & (size - 1), 0u) << "a block of " << size;
      ASSERT_EQ(n % size, 0u) << "block at " << n << " not aligned";
      const int k = std::countr_zero(size);
      std::vector<Vec2> u;
      for (uint32_t i = n; i < next; ++i) u.push_back(Sampler(SamplerKind::Sobol, 7, pixel, i).get2d());
      for (int j = 0; j <= k; ++j) {
        std::vector<int> cells(size, 0);
        for (const Vec2& p : u)
          ++cells[std::size_t(int(p.x * float(1 << j)) * (1 << (k - j)) + int(p.y * float(1 << (k - j))))];
        for (int c : cells) ASSERT_EQ(c, 1) << "pixel " << pixel << " block [" << n << ", " << next << ") split " << j;
      }
      ++blocks;
      n = next;
    }
  }
  EXPECT_EQ(blocks, 2 * 18);  // 32 -> 128 by 16 (6), -> 256 by 32 (4), -> 512 by 64 (4), -> 1024 by 128 (4)
}

RenderOptions adaptive_options(double threshold, int spp, uint64_t seed) {
  RenderOptions o;
  o.spp = spp;
  o.seed = seed;
  o.threads = 2;
  o.adaptive.noise_threshold = threshold;
  return o;
}

// The threshold is honoured: at the end, every pixel that stopped short of the maximum
// has itself and its 3x3 neighbourhood at or below the threshold; the others took the
// maximum. The test scene has both (a background that converges at once, and glass).
TEST(AdaptiveSampling, NoPixelStopsWhileItsNeighbourhoodIsAboveTheThreshold) {
  Diagnostics diag;
  auto sc = build_render_scene(testing::small_scene(), diag);
  const double threshold = 0.01;
  const RenderResult r = render_image(*sc, adaptive_options(threshold, 512, 5));
  std::vector<float> nearby(r.noise_error.size());
  neighbourhood_max(r.noise_error, r.width, r.height, nearby);
  int stopped = 0, at_max = 0;
  for (std::size_t p = 0; p < nearby.size(); ++p) {
    if (r.sample_counts[p] < 512) {
      ++stopped;
      EXPECT_LE(nearby[p], threshold) << "pixel " << p << " stopped at " << r.sample_counts[p];
      EXPECT_GE(r.sample_counts[p], 32u);  // the default minimum for 512
    } else {
      ++at_max;
    }
  }
  EXPECT_GT(stopped, 100);
  EXPECT_GT(at_max, 10);
  EXPECT_EQ(r.converged_pixels,
            uint64_t(std::count_if(nearby.begin(), nearby.end(), [&](float e) { return e <= threshold; })));
}

// Stopping early keeps the mean: an adaptive render (independent samples, so that each
// pixel's sample variance is its estimator's) against a uniform one of 1024 samples per
// pixel, in 12 regions of 10 x 10 pixels and each channel, within 4 standard errors.
TEST(AdaptiveSampling, TheMeanOfAnAdaptiveRenderIsUnchanged) {
  Diagnostics diag;
  auto sc = build_render_scene(testing::small_scene(), diag);
  auto film_of = [&](RenderOptions o) {
    std::optional<Film> film;
    o.sampler = SamplerKind::Independent;
    o.checkpoint = [&](const Film& f) { film = f; };
    render_image(*sc, o);
    return *film;
  };
  const Film adaptive = film_of(adaptive_options(0.02, 1024, 21));
  const Film uniform = film_of(adaptive_options(0, 1024, 22));
  uint64_t taken = 0;
  for (uint32_t s : adaptive.samples) taken += s;
  EXPECT_LT(double(taken), 0.8 * 1024 * double(adaptive.pixel_count()));  // it did stop early
  testing::expect_same_region_means(statistics_of(adaptive), statistics_of(uniform), 10, 10);
}

// The same seed gives the same image and counts whatever the thread count, and a render
// interrupted in an adaptive pass and resumed from its film equals one never stopped.
TEST(AdaptiveSampling, DeterministicAndResumableBitForBit) {
  Diagnostics diag;
  auto sc = build_render_scene(testing::small_scene(), diag);
  RenderOptions o = adaptive_options(0.05, 256, 9);
  o.threads = 1;
  const RenderResult one = render_image(*sc, o);
  o.threads = 2;
  const RenderResult two = render_image(*sc, o);
  ASSERT_EQ(one.rgb.size(), two.rgb.size());
  EXPECT_EQ(0, std::memcmp(one.rgb.data(), two.rgb.data(), one.rgb.size() * sizeof(float)));
  EXPECT_EQ(one.sample_counts, two.sample_counts);
  EXPECT_LT(one.min_spp, one.max_spp);

  // Stopped on one thread after 4 tiles of an adaptive pass (past the 16 samples every
  // pixel takes first): pixels then differ from their pass's target.
  std::atomic<bool> cancel{false};
  std::atomic<int64_t> samples{0};
  std::optional<Film> saved;
  RenderOptions stopped = o;
  stopped.threads = 1;
  stopped.cancel = &cancel;
  int tiles_after_uniform = 0;
  stopped.progress = [&](int64_t n) {
    if ((samples += n) > 16 * 40 * 30 && ++tiles_after_uniform == 4) cancel = true;
  };
  stopped.checkpoint = [&](const Film& f) { saved = f; };
  const RenderResult part = render_image(*sc, stopped);
  ASSERT_TRUE(part.interrupted && saved);
  bool mid_pass = false;
  for (std::size_t p = 0; p < saved->pixel_count(); ++p) mid_pass = mid_pass || saved->samples[p] < saved->target[p];
  EXPECT_TRUE(mid_pass);
  RenderOptions rest = o;
  rest.resume = &*saved;
  const RenderResult resumed = render_image(*sc, rest);
  EXPECT_EQ(resumed.rgb, two.rgb);
  EXPECT_EQ(resumed.sample_counts, two.sample_counts);
}

}  // namespace
}  // namespace dermis
