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
#include "dermis/render/path/sampler_regions.h"
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

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

// This process's tiles: the same ones in every pass (a pixel's samples are summed by one
// process, in sample order).
std::vector<Tile> own_tiles(int w, int h, const ProcessGroup& group, TileAssignment assignment) {
  std::vector<Tile> all_tiles, tiles;
  for (int y = 0; y < h; y += kTileSize)
    for (int x = 0; x < w; x += kTileSize)
      all_tiles.push_back({x, y, std::min(x + kTileSize, w), std::min(y + kTileSize, h)});
  for (std::size_t i = 0; i < all_tiles.size(); ++i)
    if (tile_owner(i, all_tiles.size(), group, assignment) == group.rank()) tiles.push_back(all_tiles[i]);
  return tiles;
}

// One render of an image: the film, this process's tiles, and the passes over them.
class ImageRender {
 public:
  ImageRender(const RenderScene& sc, const RenderOptions& opt)
      : sc_(sc),
        opt_(opt),
        start_(Clock::now()),
        bounds_(film_pixel_bounds(sc.film)),
        w_(bounds_.width()),
        h_(bounds_.height()),
        film_(w_, h_),
        filter_(sc.film.filter),
        group_(opt.group ? *opt.group : single_process()),
        tiles_(own_tiles(w_, h_, group_, opt.tile_assignment)),
        spp_(uint32_t(opt.spp)),
        spectral_(opt.spectral) {
    if (opt.resume) {
      if (opt.resume->width != w_ || opt.resume->height != h_)
        throw std::invalid_argument("render_image: the film to resume has another size than the image");
      if (group_size(opt) > 1) throw std::invalid_argument("render_image: resuming is for one process only");
      film_ = *opt.resume;
    }
    camera_path_.subsurface_strategies = &strategies_;
    const AdaptiveSampling& adaptive = opt.adaptive;
    min_spp_ = !adaptive.enabled()    ? spp_
               : adaptive.min_spp > 0 ? std::min<uint32_t>(uint32_t(adaptive.min_spp), spp_)
                                      : uint32_t(default_min_spp(opt.spp));
    if (adaptive.enabled()) error_.resize(film_.pixel_count()), nearby_error_.resize(film_.pixel_count());
  }

  RenderResult run() {
    const int threads = opt_.threads > 0 ? opt_.threads : tbb::this_task_arena::max_concurrency();
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, std::size_t(threads));
    tbb::task_arena arena(threads);
    choose_subsurface_strategies(arena);
    run_passes(arena);
    return finish();
  }

 private:
  // The subsurface materials' strategies, measured before the image (subsurface_pilot.h):
  // every process of a group, and a resumed render, makes the same choice.
  void choose_subsurface_strategies(tbb::task_arena& arena) {
    if (subsurface_pilot_wanted(sc_)) {
      const auto pilot_start = Clock::now();
      SubsurfacePilotOptions pilot;
      pilot.seed = opt_.seed;
      pilot.spp = opt_.spp;
      pilot.bounds = bounds_;
      pilot.full_width = sc_.film.xres;
      pilot.cancel = opt_.cancel;
      arena.execute([&] { result_.subsurface_choices = run_subsurface_pilot(sc_, pilot); });
      result_.pilot_seconds = seconds_since(pilot_start);
    }
    strategies_ = subsurface_strategies(sc_, result_.subsurface_choices);
  }

  // One pixel's samples, from those it has up to its target, in sample order.
  int64_t render_pixel(int x, int y, PathCounters& counters, uint64_t& bad) {
    const std::size_t pixel = std::size_t(y) * w_ + x;  // in the film
    const uint32_t first_sample = film_.samples[pixel], up_to = film_.target[pixel];
    if (up_to <= first_sample) return 0;
    // Each pixel keeps its full-image index, so a crop equals that part of the full image.
    const int image_x = bounds_.x0 + x, image_y = bounds_.y0 + y;
    const std::size_t image_pixel = std::size_t(image_y) * sc_.film.xres + image_x;
    const uint64_t rays_before = counters.rays;
    double sum[3], sum_sq[3];
    for (int c = 0; c < 3; ++c) sum[c] = film_.sum[3 * pixel + c], sum_sq[c] = film_.sum_sq[3 * pixel + c];
    const uint64_t pixel_key = Sampler::pixel_key(opt_.seed, image_pixel);
    for (uint32_t s = first_sample; s < up_to; ++s) {
      Sampler sampler(opt_.sampler, opt_.seed, image_pixel, s, pixel_key);
      Vec2 offset = filter_.sample(sampler.get2d());  // dimensions 0, 1
      Vec2 film_pos{float(image_x) + 0.5f + offset.x, float(image_y) + 0.5f + offset.y};
      // 2, 3: the lens. A pinhole takes none: hashing them was a quarter of the cost of
      // a sample that meets only the sky (trace_path starts at its own dimension).
      const Vec2 u_lens = sc_.camera.has_lens() ? sampler.get2d() : Vec2{0.5f, 0.5f};
      Ray ray = sc_.camera.generate_ray(film_pos, u_lens);
      RGB L;
      if (spectral_) {
        // The wavelengths from a region of their own: the path's dimensions are an RGB render's.
        sampler.set_dimension(Sampler::region(kCameraDimensions, kWavelengthsRegion));
        SampledWavelengths wavelengths = SampledWavelengths::sample_visible(sampler.get1d());
        PathStart start = camera_path_;
        start.wavelengths = &wavelengths;
        L = wavelengths.to_linear_srgb(trace_path(sc_, ray, sc_.camera_medium, sampler, counters, start));
      } else {
        L = trace_path(sc_, ray, sc_.camera_medium, sampler, counters, camera_path_);
      }
      if (!L.is_finite()) {
        ++bad;  // never reaches the film: counted as a zero sample and reported
        continue;
      }
      for (int c = 0; c < 3; ++c) sum[c] += L[c], sum_sq[c] += double(L[c]) * L[c];
    }
    for (int c = 0; c < 3; ++c) film_.sum[3 * pixel + c] = sum[c], film_.sum_sq[3 * pixel + c] = sum_sq[c];
    film_.samples[pixel] = up_to;
    film_.rays[pixel] += counters.rays - rays_before;
    return up_to - first_sample;
  }

  void render_tile(const Tile& t) {
    PathCounters counters;
    uint64_t bad = 0;
    int64_t taken = 0;
    for (int y = t.y0; y < t.y1; ++y)
      for (int x = t.x0; x < t.x1; ++x) taken += render_pixel(x, y, counters, bad);
    nonfinite_ += bad;
    rays_ += counters.rays;
    truncated_ += counters.truncated;
    pass_samples_ += taken;
    if (opt_.tile_rendered && taken > 0) opt_.tile_rendered(film_, t.x0, t.y0, t.x1, t.y1);
    if (opt_.progress && taken > 0) opt_.progress(taken);
  }

  // f(pixel) for each pixel this process owns.
  template <class F>
  void for_own_pixels(F&& f) const {
    for (const Tile& t : tiles_)
      for (int y = t.y0; y < t.y1; ++y)
        for (int x = t.x0; x < t.x1; ++x) f(std::size_t(y) * w_ + x);
  }

  uint32_t fewest_samples() const {
    uint32_t fewest = spp_;
    for_own_pixels([&](std::size_t p) { fewest = std::min(fewest, film_.samples[p]); });
    return fewest;
  }

  // Sets the next pass's targets; false when there is none. Up to min_spp (every pixel;
  // without adaptive sampling, the whole count), passes of 1, 1, 2, 4, ... samples per
  // pixel (at most 16), so that an interrupt or the time limit leaves every pixel with a
  // similar number of samples. Then, with adaptive sampling, passes in which the pixels
  // whose neighbourhood is above the threshold take more (adaptive_sampling.h), until
  // none is left.
  bool plan_pass() {
    if (done_ < min_spp_) {
      // Every pixel: passes of 1, 1, 2, 4, ..., 16 (a resumed film: as many as it has).
      const uint32_t n = std::min(std::clamp<uint32_t>(done_, 1, 16), min_spp_ - done_);
      for_own_pixels([&](std::size_t p) { film_.target[p] = std::max(film_.samples[p], done_ + n); });
      done_ += n;
      return true;
    }
    if (!opt_.adaptive.enabled()) return false;
    return plan_adaptive_pass();
  }

  bool plan_adaptive_pass() {
    const float threshold = opt_.adaptive.noise_threshold;
    std::fill(error_.begin(), error_.end(), 0.0f);
    for_own_pixels([&](std::size_t p) { error_[p] = pixel_noise_error(film_, p, sc_.film.exposure_scale); });
    if (group_.size() > 1) group_.sum_all(std::span<float>(error_));  // each pixel from its owner, others add 0
    neighbourhood_max(error_, w_, h_, nearby_error_);
    int64_t active = 0, skipped = 0, converged = 0;
    for (float e : nearby_error_) converged += e <= threshold ? 1 : 0;
    for_own_pixels([&](std::size_t p) {
      const bool go_on = nearby_error_[p] > threshold && film_.samples[p] < spp_;
      film_.target[p] = go_on ? next_adaptive_count(film_.samples[p], spp_) : film_.samples[p];
      active += go_on ? 1 : 0;
      if (!go_on) skipped += int64_t(spp_) - int64_t(film_.samples[p]);
    });
    if (skipped > credited_) {  // the progress learns of the samples pixels that stopped will not take
      if (opt_.progress) opt_.progress(skipped - credited_);
      pass_samples_ += skipped - credited_;
      credited_ = skipped;
    }
    if (opt_.adaptive_progress) opt_.adaptive_progress(converged, int64_t(film_.pixel_count()));
    return group_.any(active > 0);
  }

  // The tiles rendered in parallel; stopped by Ctrl-C anywhere, by the time limit only once
  // every pixel has a sample (an image with unrendered tiles is no picture).
  void render_pass(tbb::task_arena& arena) {
    const bool time_may_stop = fewest_samples() >= 1;
    arena.execute([&] {
      tbb::parallel_for(std::size_t(0), tiles_.size(), [&](std::size_t i) {
        if (stop_.load(std::memory_order_relaxed)) return;
        if ((opt_.cancel && opt_.cancel->load(std::memory_order_relaxed))) {
          stop_ = true;
          interrupted_ = true;
          return;
        }
        if (time_may_stop && opt_.time_limit > 0 && seconds_since(start_) >= opt_.time_limit) {
          stop_ = true;
          time_limited_ = true;
          return;
        }
        render_tile(tiles_[i]);
      });
    });
  }

  // The pass boundary of a group: all processes stop together, and the progress learns
  // the others' samples.
  void end_pass_in_group() {
    int64_t state[3] = {interrupted_ ? 1 : 0, time_limited_ ? 1 : 0, pass_samples_.load()};
    group_.sum_all(state);
    if (state[0] > 0) interrupted_ = true;
    if (state[1] > 0) time_limited_ = true;
    if (state[0] > 0 || state[1] > 0) stop_ = true;
    if (opt_.progress && state[2] > pass_samples_) opt_.progress(state[2] - pass_samples_);
  }

  void run_passes(tbb::task_arena& arena) {
    // A resumed film finishes the pass it was stopped in (its pixels below their target).
    bool pass_pending = false;
    if (opt_.resume)
      for (std::size_t p = 0; p < film_.pixel_count(); ++p) {
        film_.target[p] = std::min(film_.target[p], spp_);  // a resume with fewer samples takes none
        pass_pending = pass_pending || film_.samples[p] < film_.target[p];
      }
    if (opt_.resume && !pass_pending) done_ = fewest_samples();
    auto last_checkpoint = Clock::now();
    while (!stop_) {
      pass_samples_ = 0;
      if (pass_pending) {
        pass_pending = false;
        done_ = std::numeric_limits<uint32_t>::max();  // set below, from the pixels
      } else if (!plan_pass()) {
        break;
      }
      const auto pass_start = Clock::now();
      render_pass(arena);
      busy_ += seconds_since(pass_start);
      if (done_ == std::numeric_limits<uint32_t>::max()) done_ = fewest_samples();  // a resumed pass finished
      const bool finished = fewest_samples() >= spp_;  // no pass follows: no checkpoint needed
      if (opt_.checkpoint && !stop_ && !finished && seconds_since(last_checkpoint) >= opt_.checkpoint_interval) {
        opt_.checkpoint(film_);
        last_checkpoint = Clock::now();
      }
      if (group_.size() > 1) end_pass_in_group();
    }
  }

  // The film gathered on the root process and resolved, with the render's counts.
  RenderResult finish() {
    // Each pixel was summed by its owner only; the others hold zeros, and x + 0 == x.
    uint64_t counts[3] = {nonfinite_.load(), rays_.load(), truncated_.load()};
    if (group_.size() > 1) {
      group_.sum_to_root(std::span<double>(film_.sum));
      group_.sum_to_root(std::span<double>(film_.sum_sq));
      group_.sum_to_root(std::span<uint32_t>(film_.samples));
      group_.sum_to_root(std::span<uint64_t>(film_.rays));
      group_.sum_to_root(std::span<uint64_t>(counts));
    }
    if (opt_.checkpoint) opt_.checkpoint(film_);  // the state at the end: resumable to more samples
    RenderResult& result = result_;
    result.process_seconds.assign(std::size_t(group_.size()), 0.0);
    group_.gather_to_root(busy_, result.process_seconds);

    result.interrupted = interrupted_;
    result.time_limited = time_limited_;
    result.width = w_;
    result.height = h_;
    result.rgb = film_.resolve();
    if (sc_.film.exposure_scale != 1)
      for (float& v : result.rgb) v *= sc_.film.exposure_scale;
    result.nonfinite = counts[0];
    result.rays = counts[1];
    result.truncated = counts[2];
    result.min_spp = *std::min_element(film_.samples.begin(), film_.samples.end());
    result.max_spp = *std::max_element(film_.samples.begin(), film_.samples.end());
    for (uint32_t s : film_.samples) result.samples += s;
    result.noise_error.resize(film_.pixel_count());
    noise_error_map(film_, sc_.film.exposure_scale, result.noise_error);
    if (opt_.adaptive.enabled()) {  // as the passes count them: with their neighbourhood
      neighbourhood_max(result.noise_error, w_, h_, nearby_error_);
      for (float e : nearby_error_) result.converged_pixels += e <= opt_.adaptive.noise_threshold ? 1 : 0;
    }
    result.sample_counts = std::move(film_.samples);
    result.pixel_rays = std::move(film_.rays);
    result.seconds = seconds_since(start_);
    return std::move(result_);
  }

  const RenderScene& sc_;
  const RenderOptions& opt_;
  const Clock::time_point start_;
  // The pixels rendered: the crop window's.
  const PixelBounds bounds_;
  const int w_, h_;
  Film film_;
  FilterSampler filter_;
  ProcessGroup& group_;
  const std::vector<Tile> tiles_;
  const uint32_t spp_;
  const bool spectral_;  // RenderOptions::spectral, where the scene allows it
  uint32_t min_spp_ = 0;
  // The count every pixel has reached in the passes taken by all (the processes of a
  // group keep it in step).
  uint32_t done_ = 0;
  int64_t credited_ = 0;  // samples the progress was told of for pixels that stopped early
  double busy_ = 0;
  std::vector<float> error_, nearby_error_;
  // The camera paths: each subsurface material with its strategy (the pilot's).
  std::vector<int> strategies_;
  PathStart camera_path_;
  std::atomic<uint64_t> nonfinite_{0}, rays_{0}, truncated_{0};
  std::atomic<int64_t> pass_samples_{0};
  std::atomic<bool> stop_{false}, interrupted_{false}, time_limited_{false};
  RenderResult result_;
};

}  // namespace

std::string spectral_limitations(const RenderScene& sc) {
  for (const auto& m : sc.subsurface)
    if (std::holds_alternative<PointCloudMethod>(m->method))
      return "the point-cloud method has no spectral form: its cloud is computed in RGB and the colour of its light "
             "is uplifted to the path's wavelengths";
  return {};
}

RenderResult render_image(const RenderScene& sc, const RenderOptions& opt) { return ImageRender(sc, opt).run(); }

}  // namespace dermis
