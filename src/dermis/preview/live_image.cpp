#include "dermis/preview/live_image.h"

#include <algorithm>
#include <cmath>

#include "dermis/render/adaptive_sampling.h"

namespace dermis {

const char* live_image_state_name(LiveImage::State s) {
  switch (s) {
    case LiveImage::State::Loading:
      return "loading";
    case LiveImage::State::Rendering:
      return "rendering";
    case LiveImage::State::Done:
      return "done";
    case LiveImage::State::Interrupted:
      return "interrupted";
    case LiveImage::State::Error:
      return "error";
  }
  return "unknown";
}

LiveImage::LiveImage(std::string scene) { status_.scene = std::move(scene); }

void LiveImage::begin_loading() {
  std::lock_guard lock(mutex_);
  status_.state = State::Loading;
}

void LiveImage::begin_render(int width, int height, int spp, int64_t total_samples, double exposure_scale) {
  std::lock_guard lock(mutex_);
  ++status_.render;
  status_.state = State::Rendering;
  status_.error.clear();
  status_.spp = spp;
  status_.converged.reset();
  total_ = std::max<int64_t>(total_samples, 1);
  done_ = 0;
  exposure_scale_ = exposure_scale;
  started_ = Clock::now();
  if (pixels_.width != width || pixels_.height != height) {
    const std::size_t n = std::size_t(width) * std::size_t(height);
    pixels_.width = width, pixels_.height = height;
    pixels_.rgb.assign(3 * n, 0.0f);
    pixels_.samples.assign(n, 0);
    pixels_.error.assign(n, -1.0f);
    ++pixels_.frame;
  }
  std::fill(pixels_.samples.begin(), pixels_.samples.end(), 0u);
  taken_ = 0;
}

void LiveImage::copy_tile(const Film& film, int x0, int y0, int x1, int y1) {
  // Computed before taking the lock: the render's thread waits for no reader longer than a copy.
  const int w = x1 - x0;
  std::vector<float> rgb(3 * std::size_t(w) * std::size_t(y1 - y0)), error(std::size_t(w) * std::size_t(y1 - y0));
  std::vector<uint32_t> samples(error.size());
  double scale;
  {
    std::lock_guard lock(mutex_);
    scale = exposure_scale_;
  }
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) {
      const std::size_t p = std::size_t(y) * film.width + x, t = std::size_t(y - y0) * w + (x - x0);
      const uint32_t n = film.samples[p];
      for (int c = 0; c < 3; ++c) rgb[3 * t + c] = n > 0 ? float(film.sum[3 * p + c] / n * scale) : 0.0f;
      samples[t] = n;
      const float e = pixel_noise_error(film, p, scale);
      error[t] = std::isfinite(e) ? e : -1.0f;
    }
  std::lock_guard lock(mutex_);
  if (film.width != pixels_.width || film.height != pixels_.height) return;  // not this render's film
  for (int y = y0; y < y1; ++y) {
    const std::size_t row = std::size_t(y) * pixels_.width, t = std::size_t(y - y0) * w;
    for (int x = 0; x < w; ++x) taken_ += int64_t(samples[t + x]) - int64_t(pixels_.samples[row + x0 + x]);
    std::copy_n(&rgb[3 * t], 3 * w, &pixels_.rgb[3 * (row + x0)]);
    std::copy_n(&samples[t], w, &pixels_.samples[row + x0]);
    std::copy_n(&error[t], w, &pixels_.error[row + x0]);
  }
  ++pixels_.frame;
}

void LiveImage::add_samples(int64_t n) {
  std::lock_guard lock(mutex_);
  done_ += n;
}

void LiveImage::set_converged(double share) {
  std::lock_guard lock(mutex_);
  status_.converged = share;
}

void LiveImage::finish(bool interrupted) {
  std::lock_guard lock(mutex_);
  status_.state = interrupted ? State::Interrupted : State::Done;
  finished_ = Clock::now();
}

void LiveImage::fail(std::string message) {
  std::lock_guard lock(mutex_);
  status_.state = State::Error;
  status_.error = std::move(message);
}

LiveImage::Status LiveImage::status() const {
  std::lock_guard lock(mutex_);
  Status s = status_;
  s.frame = pixels_.frame;
  s.width = pixels_.width, s.height = pixels_.height;
  if (s.state == State::Loading && s.render == 0) return s;
  const bool running = status_.state == State::Rendering;
  s.elapsed = std::chrono::duration<double>((running ? Clock::now() : finished_) - started_).count();
  if (status_.state == State::Error || status_.state == State::Loading) s.elapsed = 0;
  const std::size_t pixels = pixels_.samples.size();
  const int64_t done = std::min(done_, total_);
  s.samples_per_pixel = pixels > 0 ? double(taken_) / double(pixels) : 0;
  s.progress = s.state == State::Done ? 1.0 : double(done) / double(total_);
  if (running && done > 0) s.eta = s.elapsed * double(total_ - done) / double(done);
  if (s.state == State::Done) s.eta = 0.0;
  return s;
}

bool LiveImage::frame_since(uint64_t since, Frame& out) const {
  std::lock_guard lock(mutex_);
  if (pixels_.frame == since) return false;
  out = pixels_;
  return true;
}

}  // namespace dermis
