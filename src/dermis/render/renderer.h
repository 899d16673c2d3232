// The render loop: image tiles in parallel (oneTBB), samples in passes so that a
// time limit or an interrupt stops between tiles with a consistent image. Each
// pixel sample draws its numbers from Sampler(kind, seed, pixel, sample) (core/sampler.h)
// and each pixel is accumulated by one thread in sample order: the same seed gives the
// same image whatever the number of threads. With a ProcessGroup of several processes
// each tile belongs to one process for the whole render, so each pixel's sum is taken
// in the same order as by one process: the same image whatever the number of processes.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "dermis/core/sampler.h"
#include "dermis/render/adaptive_sampling.h"
#include "dermis/render/film.h"
#include "dermis/render/process_group.h"
#include "dermis/render/render_scene.h"
#include "dermis/render/subsurface_pilot.h"

namespace dermis {

// Which process of a group renders which tile (of 16x16 pixels, row-major).
enum class TileAssignment {
  Interleaved,  // tile i to process i mod N: heavy regions spread over the processes
  Blocks,       // contiguous runs of tiles, one per process (ProcessGroup::share)
};

// What a spectral render of `sc` does in RGB (empty: nothing), for a warning that names the
// method and what it does instead: the point-cloud method's cloud is RGB, and its light's
// colour is uplifted to the path's wavelengths (subsurface/point_cloud_method.h).
std::string spectral_limitations(const RenderScene& sc);

struct RenderOptions {
  int spp = 16;
  int threads = 0;  // 0: all cores
  uint64_t seed = 0;
  SamplerKind sampler = SamplerKind::Sobol;
  // Spectral transport (--spectral): each camera sample carries kPathWavelengths wavelengths
  // (spectral/sampled_wavelengths.h), its RGB inputs read as pbrt-v4 reads them, and the film
  // records the colour of its values (CIE 1931 to linear sRGB). What stays RGB inside a
  // spectral render: spectral_limitations.
  bool spectral = false;
  double time_limit = 0;                      // seconds; 0: none
  const std::atomic<bool>* cancel = nullptr;  // set (e.g. by SIGINT) to stop early
  // Called from worker threads with the number of pixel samples just finished; with a
  // group, also at each pass boundary with the samples the other processes finished.
  std::function<void(int64_t)> progress;
  // Adaptive sampling (adaptive_sampling.h): `spp` is then the most a pixel takes. The
  // progress is also told the samples a pixel will not take once it stops early.
  AdaptiveSampling adaptive;
  // With adaptive sampling, called at each pass boundary with the pixels whose
  // neighbourhood is below the threshold, out of all (the whole image, on every process).
  std::function<void(int64_t converged, int64_t pixels)> adaptive_progress;
  // The processes sharing the render (null: this one alone). The film is summed to
  // rank 0: only rank 0's result holds the image and the totals.
  ProcessGroup* group = nullptr;
  TileAssignment tile_assignment = TileAssignment::Interleaved;
  // Continue from this film (a checkpoint of the same scene, seed and sampler; the
  // crop window's size): each pixel goes on from the samples it has, in sample order,
  // so the result is bit-identical to a render never stopped. One process only.
  const Film* resume = nullptr;
  // Called between passes (on the calling thread, the film consistent) once at least
  // checkpoint_interval seconds passed since the last call, and once at the end.
  std::function<void(const Film&)> checkpoint;
  double checkpoint_interval = 60;
  // Called on the worker thread that has just rendered the tile [x0, x1) x [y0, y1) of
  // the film (film pixels) in a pass, its pixels consistent and written by no other
  // thread until the call returns: a live preview copies them (preview/live_image.h).
  std::function<void(const Film&, int x0, int y0, int x1, int y1)> tile_rendered;
};

struct RenderResult {
  int width = 0, height = 0;
  std::vector<float> rgb;  // linear, row-major, top row first
  uint64_t samples = 0;    // pixel samples in the image (a resumed film's included)
  uint64_t nonfinite = 0;  // samples that were NaN or infinite (counted as zero)
  uint64_t rays = 0;
  uint64_t truncated = 0;
  uint32_t min_spp = 0, max_spp = 0;
  // Per pixel (rank 0 only): the samples taken and the estimated error of the pixel's
  // value (adaptive_sampling.h, pixel_noise_error: the image's own noise, whether or not
  // the render was adaptive).
  std::vector<uint32_t> sample_counts;
  std::vector<uint64_t> pixel_rays;  // rays traced per pixel: where the time went
  std::vector<float> noise_error;
  uint64_t converged_pixels = 0;  // pixels whose 3x3 neighbourhood is at or below the noise threshold (adaptive only)
  double seconds = 0;
  // Seconds each process spent rendering its tiles, waits at pass boundaries excluded
  // (rank 0 only; one entry per process).
  std::vector<double> process_seconds;
  // What the pilot chose per subsurface material (subsurface_pilot.h; empty without one),
  // and the seconds it took (within `seconds`).
  std::vector<SubsurfaceChoice> subsurface_choices;
  double pilot_seconds = 0;
  bool interrupted = false;   // stopped by `cancel`
  bool time_limited = false;  // stopped by the time limit
};

RenderResult render_image(const RenderScene& scene, const RenderOptions& options);

}  // namespace dermis
