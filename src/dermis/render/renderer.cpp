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

int tile_owner(std::size_t tile, std::size_t tiles, const ProcessGroup& group, TileAssignment assignment) {
  if (assignment == TileAssignment::Interleaved) return int(tile % std::size_t(group.size()));
  for (int r = 0; r < group.size(); ++r)
    if (tile < group.share_of(r, tiles).second) return r;
  return group.size() - 1;
}

int group_size(const RenderOptions& opt) { return opt.group ? opt.group->size() : 1; }

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
  if (opt.resume) {
    if (opt.resume->width != w || opt.resume->height != h)
      throw std::invalid_argument("render_image: the film to resume has another size than the image");
    if (group_size(opt) > 1) throw std::invalid_argument("render_image: resuming is for one process only");
    film = *opt.resume;
  }
  FilterSampler filter(sc.film.filter);

  // This process's tiles: the same ones in every pass (a pixel's samples are summed
  // by one process, in sample order).
  ProcessGroup& group = opt.group ? *opt.group : single_process();
  std::vector<Tile> all_tiles, tiles;
  for (int y = 0; y < h; y += kTileSize)
    for (int x = 0; x < w; x += kTileSize) all_tiles.push_back({x, y, std::min(x + kTileSize, w), std::min(y + kTileSize, h)});
  for (std::size_t i = 0; i < all_tiles.size(); ++i)
    if (tile_owner(i, all_tiles.size(), group, opt.tile_assignment) == group.rank()) tiles.push_back(all_tiles[i]);

  std::atomic<uint64_t> nonfinite{0}, rays{0}, truncated{0};
  std::atomic<int64_t> pass_samples{0};
  std::atomic<bool> stop{false}, interrupted{false}, time_limited{false};
  RenderResult result;
  auto out_of_time = [&] {
    return opt.time_limit > 0 && std::chrono::duration<double>(Clock::now() - start).count() >= opt.time_limit;
  };

  // Samples [first, up_to) of each pixel of the tile, where `first` is what its pixels
  // have (every pixel of a tile has the same count).
  auto render_tile = [&](const Tile& t, int up_to) {
    const int first_sample = int(film.samples[std::size_t(t.y0) * w + t.x0]);
    const int n_samples = up_to - first_sample;
    if (n_samples <= 0) return;
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
    const int64_t taken = int64_t(t.x1 - t.x0) * (t.y1 - t.y0) * n_samples;
    pass_samples += taken;
    if (opt.progress) opt.progress(taken);
  };

  const int threads = opt.threads > 0 ? opt.threads : tbb::this_task_arena::max_concurrency();
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, std::size_t(threads));
  tbb::task_arena arena(threads);

  // Passes of 1, 1, 2, 4, ... samples per pixel (at most 16), so that an interrupt or
  // the time limit leaves every pixel with a similar number of samples.
  // A resumed film goes on from its fewest samples; tiles that have more skip ahead.
  int done = opt.resume ? int(*std::min_element(film.samples.begin(), film.samples.end())) : 0;
  int pass_size = std::clamp(done, 1, 16);
  double busy = 0;
  auto last_checkpoint = Clock::now();
  while (done < opt.spp && !stop) {
    int n = std::min({pass_size, opt.spp - done, 16});
    pass_samples = 0;
    const auto pass_start = Clock::now();
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
        render_tile(tiles[i], done + n);
      });
    });
    busy += std::chrono::duration<double>(Clock::now() - pass_start).count();
    done += n;
    if (done > 1) pass_size = std::min(pass_size * 2, 16);
    if (opt.checkpoint && !stop && done < opt.spp &&
        std::chrono::duration<double>(Clock::now() - last_checkpoint).count() >= opt.checkpoint_interval) {
      opt.checkpoint(film);
      last_checkpoint = Clock::now();
    }
    if (group.size() > 1) {
      // The pass boundary: all processes stop together, and the progress learns the
      // others' samples.
      int64_t state[3] = {interrupted ? 1 : 0, time_limited ? 1 : 0, pass_samples.load()};
      group.sum_all(state);
      if (state[0] > 0) interrupted = true;
      if (state[1] > 0) time_limited = true;
      if (state[0] > 0 || state[1] > 0) stop = true;
      if (opt.progress && state[2] > pass_samples) opt.progress(state[2] - pass_samples);
    }
  }

  // Each pixel was summed by its owner only; the others hold zeros, and x + 0 == x.
  uint64_t counts[3] = {nonfinite.load(), rays.load(), truncated.load()};
  if (group.size() > 1) {
    group.sum_to_root(std::span<double>(film.sum));
    group.sum_to_root(std::span<uint32_t>(film.samples));
    group.sum_to_root(std::span<uint64_t>(counts));
  }
  if (opt.checkpoint) opt.checkpoint(film);  // the state at the end: resumable to more samples
  result.process_seconds.assign(std::size_t(group.size()), 0.0);
  group.gather_to_root(busy, result.process_seconds);

  result.interrupted = interrupted;
  result.time_limited = time_limited;
  result.width = w;
  result.height = h;
  result.rgb = film.resolve();
  if (sc.film.exposure_scale != 1)
    for (float& v : result.rgb) v *= sc.film.exposure_scale;
  result.nonfinite = counts[0];
  result.rays = counts[1];
  result.truncated = counts[2];
  result.min_spp = *std::min_element(film.samples.begin(), film.samples.end());
  result.max_spp = *std::max_element(film.samples.begin(), film.samples.end());
  for (uint32_t s : film.samples) result.samples += s;
  result.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return result;
}

}  // namespace dermis
