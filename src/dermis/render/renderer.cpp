#include "dermis/render/renderer.h"

#include <oneapi/tbb/global_control.h>
#include <oneapi/tbb/parallel_for.h>
#include <oneapi/tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <cmath>

#include "dermis/core/sampler.h"
#include "dermis/render/film.h"
#include "dermis/render/integrator.h"

namespace dermis {

namespace {

constexpr int kTileSize = 16;

struct Tile {
  int x0, y0, x1, y1;
};

}  // namespace

RenderResult render_image(const RenderScene& sc, const RenderOptions& opt) {
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  // The pixels rendered: the crop window's; each keeps its full-image index, so a crop
  // equals that part of the full image.
  const int full_w = sc.film.xres;
  const PixelBounds bounds = film_pixel_bounds(sc.film);
  const int x_begin = bounds.x0, y_begin = bounds.y0, w = bounds.width(), h = bounds.height();
  Film film(w, h);
  FilterSampler filter(sc.film.filter);

  std::vector<Tile> tiles;
  for (int y = 0; y < h; y += kTileSize)
    for (int x = 0; x < w; x += kTileSize) tiles.push_back({x, y, std::min(x + kTileSize, w), std::min(y + kTileSize, h)});

  std::atomic<uint64_t> nonfinite{0}, rays{0}, truncated{0};
  std::atomic<bool> stop{false}, interrupted{false}, time_limited{false};
  RenderResult result;
  auto out_of_time = [&] {
    return opt.time_limit > 0 && std::chrono::duration<double>(Clock::now() - start).count() >= opt.time_limit;
  };

  auto render_tile = [&](const Tile& t, int first_sample, int n_samples) {
    PathCounters counters;
    uint64_t bad = 0;
    for (int y = t.y0; y < t.y1; ++y)
      for (int x = t.x0; x < t.x1; ++x) {
        const std::size_t pixel = std::size_t(y) * w + x;  // in the film
        const int image_x = x_begin + x, image_y = y_begin + y;
        const std::size_t image_pixel = std::size_t(image_y) * full_w + image_x;
        double sum[3] = {film.sum[3 * pixel], film.sum[3 * pixel + 1], film.sum[3 * pixel + 2]};
        for (int s = first_sample; s < first_sample + n_samples; ++s) {
          Sampler sampler(opt.sampler, opt.seed, image_pixel, uint32_t(s));
          Vec2 offset = filter.sample(sampler.get2d());  // dimensions 0, 1
          Vec2 film_pos{float(image_x) + 0.5f + offset.x, float(image_y) + 0.5f + offset.y};
          Ray ray = sc.camera.generate_ray(film_pos, sampler.get2d());  // 2, 3: the lens
          RGB L = trace_path(sc, ray, sc.camera_medium, sampler, counters);
          if (!L.is_finite()) {
            ++bad;  // never reaches the film: counted as a zero sample and reported
            continue;
          }
          for (int c = 0; c < 3; ++c) sum[c] += L[c];
        }
        for (int c = 0; c < 3; ++c) film.sum[3 * pixel + c] = sum[c];
        film.samples[pixel] += uint32_t(n_samples);
      }
    nonfinite += bad;
    rays += counters.rays;
    truncated += counters.truncated;
    if (opt.progress) opt.progress(int64_t(t.x1 - t.x0) * (t.y1 - t.y0) * n_samples);
  };

  const int threads = opt.threads > 0 ? opt.threads : tbb::this_task_arena::max_concurrency();
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, std::size_t(threads));
  tbb::task_arena arena(threads);

  // Passes of 1, 1, 2, 4, ... samples per pixel (at most 16), so that an interrupt or
  // the time limit leaves every pixel with a similar number of samples.
  int done = 0, pass_size = 1;
  while (done < opt.spp && !stop) {
    int n = std::min({pass_size, opt.spp - done, 16});
    arena.execute([&] {
      tbb::parallel_for(std::size_t(0), tiles.size(), [&](std::size_t i) {
        if (stop.load(std::memory_order_relaxed)) return;
        if ((opt.cancel && opt.cancel->load(std::memory_order_relaxed))) {
          stop = true;
          interrupted = true;
          return;
        }
        if (out_of_time()) {
          stop = true;
          time_limited = true;
          return;
        }
        render_tile(tiles[i], done, n);
      });
    });
    done += n;
    if (done > 1) pass_size = std::min(pass_size * 2, 16);
  }

  result.interrupted = interrupted;
  result.time_limited = time_limited;
  result.width = w;
  result.height = h;
  result.rgb = film.resolve();
  if (sc.film.exposure_scale != 1)
    for (float& v : result.rgb) v *= sc.film.exposure_scale;
  result.nonfinite = nonfinite;
  result.rays = rays;
  result.truncated = truncated;
  result.min_spp = *std::min_element(film.samples.begin(), film.samples.end());
  result.max_spp = *std::max_element(film.samples.begin(), film.samples.end());
  for (uint32_t s : film.samples) result.samples += s;
  result.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return result;
}

}  // namespace dermis
