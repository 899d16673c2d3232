// The picture a render is making, as the live preview shows it (preview_server.h): every
// pixel's latest value, its sample count and estimated error, and the progress facts.
// Written by the render (a tile at a time, from its worker threads: RenderOptions::
// tile_rendered) and by the command that runs it; read by the server's threads.
#pragma once

#include <chrono>
#include <cstdint>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "dermis/render/film.h"

namespace dermis {

class LiveImage {
 public:
  enum class State { Loading, Rendering, Done, Interrupted, Error };

  // What status.json says (preview_server.cpp).
  struct Status {
    std::string scene;
    int render = 0;  // renders begun (a --watch restart begins another)
    State state = State::Loading;
    uint64_t frame = 0;  // changes whenever pixels do
    int width = 0, height = 0;
    int spp = 0;                      // the most a pixel takes
    double samples_per_pixel = 0;     // taken so far, on average
    double progress = 0;              // 0 to 1
    std::optional<double> converged;  // adaptive sampling: the share of pixels converged
    double elapsed = 0;               // seconds since the render began
    std::optional<double> eta;        // seconds left, from the rate so far
    std::string error;                // why the scene did not load (file:line:col: ...); empty if it did
  };

  // A film's sums as the render left them (Film): the means and errors are computed by
  // the reader, so that the render's threads only copy.
  struct Sums {
    std::vector<double> sum, sum_sq;  // 3 per pixel
    std::vector<uint32_t> samples;
  };

  // The pixels: linear RGB (the Film's exposure applied), samples, estimated error
  // (adaptive_sampling.h, pixel_noise_error; negative where unknown).
  struct Frame {
    int width = 0, height = 0;
    uint64_t frame = 0;
    std::vector<float> rgb;
    std::vector<uint32_t> samples;
    std::vector<float> error;
    Sums sums;  // what frame_since copied (kept to reuse its memory)
  };

  explicit LiveImage(std::string scene);

  // Loading the scene (again): the last image stays.
  void begin_loading();
  // A render of width x height pixels, at most spp samples each, total pixel samples in all.
  // The last image stays, replaced tile by tile, where it has the same size.
  void begin_render(int width, int height, int spp, int64_t total_samples, double exposure_scale);
  // Copies a tile just rendered (RenderOptions::tile_rendered).
  void copy_tile(const Film& film, int x0, int y0, int x1, int y1);
  void add_samples(int64_t n);
  void set_converged(double share);
  void finish(bool interrupted);
  // The scene did not load: the message is shown and the last image stays.
  void fail(std::string message);

  Status status() const;
  // The render threads' CPU seconds spent in copy_tile so far (the preview's cost to them).
  double copy_cpu_seconds() const;
  // The pixels, copied, where they changed since `since` (a Frame::frame); else false.
  // The copy takes the lock a band of rows at a time: a tile finished meanwhile waits for
  // one band, not the whole image (a frame may then show some tiles a pass newer).
  bool frame_since(uint64_t since, Frame& out) const;

 private:
  using Clock = std::chrono::steady_clock;
  mutable std::mutex mutex_;
  Status status_;
  int width_ = 0, height_ = 0;
  uint64_t frame_ = 0;  // changes whenever sums_ do
  Sums sums_;
  int64_t total_ = 0, done_ = 0;    // the progress's pixel samples (skipped ones included)
  std::vector<uint32_t> rendered_;  // the samples of this render per pixel
  int64_t taken_ = 0;               // their sum

  double exposure_scale_ = 1;
  int64_t copy_cpu_ns_ = 0;
  Clock::time_point started_{}, finished_{};
};

const char* live_image_state_name(LiveImage::State s);

}  // namespace dermis
