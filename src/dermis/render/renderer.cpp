#include "dermis/render/renderer.h"

#include <oneapi/tbb/global_control.h>
#include <oneapi/tbb/parallel_for.h>
#include <oneapi/tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "dermis/core/sampler.h"
#include "dermis/render/adaptive_sampling.h"
#include "dermis/render/film.h"
#include "dermis/render/integrator.h"
#include "dermis/render/subsurface_pilot.h"

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
    for (int x = 0; x < w; x += kTileSize)
      all_tiles.push_back({x, y, std::min(x + kTileSize, w), std::min(y + kTileSize, h)});
  for (std::size_t i = 0; i < all_tiles.size(); ++i)
    if (tile_owner(i, all_tiles.size(), group, opt.tile_assignment) == group.rank()) tiles.push_back(all_tiles[i]);

  std::atomic<uint64_t> nonfinite{0}, rays{0}, truncated{0};
  std::atomic<int64_t> pass_samples{0};
  std::atomic<bool> stop{false}, interrupted{false}, time_limited{false};
  RenderResult result;
  auto out_of_time = [&] {
    return opt.time_limit > 0 && std::chrono::duration<double>(Clock::now() - start).count() >= opt.time_limit;
  };

  // The camera paths: each subsurface material with its strategy (the pilot's, below).
  std::vector<int> strategies;
  PathStart camera_path;
  camera_path.subsurface_strategies = &strategies;

  // Each pixel of the tile, from the samples it has up to its target, in sample order.
  auto render_tile = [&](const Tile& t) {
    PathCounters counters;
    uint64_t bad = 0;
    int64_t taken = 0;
    for (int y = t.y0; y < t.y1; ++y)
      for (int x = t.x0; x < t.x1; ++x) {
        const std::size_t pixel = std::size_t(y) * w + x;  // in the film
        const uint32_t first_sample = film.samples[pixel], up_to = film.target[pixel];
        if (up_to <= first_sample) continue;
        const int image_x = x_begin + x, image_y = y_begin + y;
        const std::size_t image_pixel = std::size_t(image_y) * full_w + image_x;
        const uint64_t rays_before = counters.rays;
        double sum[3], sum_sq[3];
        for (int c = 0; c < 3; ++c) sum[c] = film.sum[3 * pixel + c], sum_sq[c] = film.sum_sq[3 * pixel + c];
        const uint64_t pixel_key = Sampler::pixel_key(opt.seed, image_pixel);
        for (uint32_t s = first_sample; s < up_to; ++s) {
          Sampler sampler(opt.sampler, opt.seed, image_pixel, s, pixel_key);
          Vec2 offset = filter.sample(sampler.get2d());  // dimensions 0, 1
          Vec2 film_pos{float(image_x) + 0.5f + offset.x, float(image_y) + 0.5f + offset.y};
          // 2, 3: the lens. A pinhole takes none: hashing them was a quarter of the cost of
          // a sample that meets only the sky (trace_path starts at its own dimension).
          const Vec2 u_lens = sc.camera.has_lens() ? sampler.get2d() : Vec2{0.5f, 0.5f};
          Ray ray = sc.camera.generate_ray(film_pos, u_lens);
          RGB L = trace_path(sc, ray, sc.camera_medium, sampler, counters, camera_path);
          if (!L.is_finite()) {
            ++bad;  // never reaches the film: counted as a zero sample and reported
            continue;
          }
          for (int c = 0; c < 3; ++c) sum[c] += L[c], sum_sq[c] += double(L[c]) * L[c];
        }
        for (int c = 0; c < 3; ++c) film.sum[3 * pixel + c] = sum[c], film.sum_sq[3 * pixel + c] = sum_sq[c];
        film.samples[pixel] = up_to;
        film.rays[pixel] += counters.rays - rays_before;
        taken += up_to - first_sample;
      }
    nonfinite += bad;
    rays += counters.rays;
    truncated += counters.truncated;
    pass_samples += taken;
    if (opt.progress && taken > 0) opt.progress(taken);
  };

  const int threads = opt.threads > 0 ? opt.threads : tbb::this_task_arena::max_concurrency();
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, std::size_t(threads));
  tbb::task_arena arena(threads);

  // The subsurface materials' strategies, measured before the image (subsurface_pilot.h):
  // every process of a group, and a resumed render, makes the same choice.
  if (subsurface_pilot_wanted(sc)) {
    const auto pilot_start = Clock::now();
    SubsurfacePilotOptions pilot;
    pilot.seed = opt.seed;
    pilot.spp = opt.spp;
    pilot.bounds = bounds;
    pilot.full_width = full_w;
    pilot.cancel = opt.cancel;
    arena.execute([&] { result.subsurface_choices = run_subsurface_pilot(sc, pilot); });
    result.pilot_seconds = std::chrono::duration<double>(Clock::now() - pilot_start).count();
  }
  strategies = subsurface_strategies(sc, result.subsurface_choices);

  // The passes. Up to min_spp (every pixel; without adaptive sampling, the whole count),
  // passes of 1, 1, 2, 4, ... samples per pixel (at most 16), so that an interrupt or the
  // time limit leaves every pixel with a similar number of samples. Then, with adaptive
  // sampling, passes in which the pixels whose neighbourhood is above the threshold take
  // more (adaptive_sampling.h), until none is left.
  const AdaptiveSampling& adaptive = opt.adaptive;
  const uint32_t spp = uint32_t(opt.spp);
  const uint32_t min_spp = !adaptive.enabled()    ? spp
                           : adaptive.min_spp > 0 ? std::min<uint32_t>(uint32_t(adaptive.min_spp), spp)
                                                  : uint32_t(default_min_spp(opt.spp));
  // A resumed film finishes the pass it was stopped in (its pixels below their target).
  bool pass_pending = false;
  if (opt.resume)
    for (std::size_t p = 0; p < film.pixel_count(); ++p) {
      film.target[p] = std::min(film.target[p], spp);  // a resume with fewer samples takes none
      pass_pending = pass_pending || film.samples[p] < film.target[p];
    }
  // f(pixel) for each pixel this process owns.
  auto for_own_pixels = [&](auto&& f) {
    for (const Tile& t : tiles)
      for (int y = t.y0; y < t.y1; ++y)
        for (int x = t.x0; x < t.x1; ++x) f(std::size_t(y) * w + x);
  };
  std::vector<float> error, nearby_error;
  if (adaptive.enabled()) error.resize(film.pixel_count()), nearby_error.resize(film.pixel_count());
  int64_t credited = 0;  // samples the progress was told of for pixels that stopped early

  // The count every pixel has reached in the passes taken by all (the processes of a
  // group keep it in step).
  uint32_t done = 0;
  auto fewest_samples = [&] {
    uint32_t fewest = spp;
    for_own_pixels([&](std::size_t p) { fewest = std::min(fewest, film.samples[p]); });
    return fewest;
  };
  if (opt.resume && !pass_pending) done = fewest_samples();
  // Sets the next pass's targets; false when there is none.
  auto plan_pass = [&]() -> bool {
    if (done < min_spp) {
      // Every pixel: passes of 1, 1, 2, 4, ..., 16 (a resumed film: as many as it has).
      const uint32_t n = std::min(std::clamp<uint32_t>(done, 1, 16), min_spp - done);
      for_own_pixels([&](std::size_t p) { film.target[p] = std::max(film.samples[p], done + n); });
      done += n;
      return true;
    }
    if (!adaptive.enabled()) return false;
    std::fill(error.begin(), error.end(), 0.0f);
    for_own_pixels([&](std::size_t p) { error[p] = pixel_noise_error(film, p, sc.film.exposure_scale); });
    if (group.size() > 1) group.sum_all(std::span<float>(error));  // each pixel from its owner, others add 0
    neighbourhood_max(error, w, h, nearby_error);
    int64_t active = 0, skipped = 0, converged = 0;
    for (float e : nearby_error) converged += e <= adaptive.noise_threshold ? 1 : 0;
    for_own_pixels([&](std::size_t p) {
      const bool go_on = nearby_error[p] > adaptive.noise_threshold && film.samples[p] < spp;
      film.target[p] = go_on ? next_adaptive_count(film.samples[p], spp) : film.samples[p];
      active += go_on ? 1 : 0;
      if (!go_on) skipped += int64_t(spp) - int64_t(film.samples[p]);
    });
    if (skipped > credited) {
      if (opt.progress) opt.progress(skipped - credited);
      pass_samples += skipped - credited;
      credited = skipped;
    }
    if (opt.adaptive_progress) opt.adaptive_progress(converged, int64_t(film.pixel_count()));
    return group.any(active > 0);
  };

  double busy = 0;
  auto last_checkpoint = Clock::now();
  while (!stop) {
    pass_samples = 0;
    if (pass_pending) {
      pass_pending = false;
      done = std::numeric_limits<uint32_t>::max();  // set below, from the pixels
    } else if (!plan_pass()) {
      break;
    }
    const auto pass_start = Clock::now();
    // The time limit stops a pass only once every pixel has a sample: an image with
    // unrendered tiles is no picture (Ctrl-C stops anywhere).
    const bool time_may_stop = fewest_samples() >= 1;
    arena.execute([&] {
      tbb::parallel_for(std::size_t(0), tiles.size(), [&](std::size_t i) {
        if (stop.load(std::memory_order_relaxed)) return;
        if ((opt.cancel && opt.cancel->load(std::memory_order_relaxed))) {
          stop = true;
          interrupted = true;
          return;
        }
        if (time_may_stop && out_of_time()) {
          stop = true;
          time_limited = true;
          return;
        }
        render_tile(tiles[i]);
      });
    });
    busy += std::chrono::duration<double>(Clock::now() - pass_start).count();
    if (done == std::numeric_limits<uint32_t>::max()) done = fewest_samples();  // a resumed pass finished
    const bool finished = fewest_samples() >= spp;                              // no pass follows: no checkpoint needed
    if (opt.checkpoint && !stop && !finished &&
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
    group.sum_to_root(std::span<double>(film.sum_sq));
    group.sum_to_root(std::span<uint32_t>(film.samples));
    group.sum_to_root(std::span<uint64_t>(film.rays));
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
  result.noise_error.resize(film.pixel_count());
  noise_error_map(film, sc.film.exposure_scale, result.noise_error);
  if (adaptive.enabled()) {  // as the passes count them: with their neighbourhood
    neighbourhood_max(result.noise_error, w, h, nearby_error);
    for (float e : nearby_error) result.converged_pixels += e <= adaptive.noise_threshold ? 1 : 0;
  }
  result.sample_counts = std::move(film.samples);
  result.pixel_rays = std::move(film.rays);
  result.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return result;
}

}  // namespace dermis
