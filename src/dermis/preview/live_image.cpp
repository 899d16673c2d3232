#include "dermis/preview/live_image.h"

#include <algorithm>
#include <cmath>

#include "dermis/preview/thread_cpu_time.h"
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
  if (width_ != width || height_ != height) {
    const std::size_t n = std::size_t(width) * std::size_t(height);
    width_ = width, height_ = height;
    sums_.sum.assign(3 * n, 0.0);
    sums_.sum_sq.assign(3 * n, 0.0);
    sums_.samples.assign(n, 0);
    ++frame_;
  }
  // The last image stays until its tiles are rendered again; this render's samples count anew.
  rendered_.assign(std::size_t(width) * std::size_t(height), 0);
  taken_ = 0;
}

void LiveImage::copy_tile(const Film& film, int x0, int y0, int x1, int y1) {
  const int64_t cpu_start = thread_cpu_ns();
  {
    std::lock_guard lock(mutex_);
    if (film.width != width_ || film.height != height_) return;  // not this render's film
    const std::size_t w = std::size_t(x1 - x0);
    for (int y = y0; y < y1; ++y) {
      const std::size_t p = std::size_t(y) * std::size_t(width_) + std::size_t(x0);
      for (std::size_t x = 0; x < w; ++x) taken_ += int64_t(film.samples[p + x]) - int64_t(rendered_[p + x]);
      std::copy_n(&film.samples[p], w, &rendered_[p]);
      std::copy_n(&film.samples[p], w, &sums_.samples[p]);
      std::copy_n(&film.sum[3 * p], 3 * w, &sums_.sum[3 * p]);
      std::copy_n(&film.sum_sq[3 * p], 3 * w, &sums_.sum_sq[3 * p]);
    }
    ++frame_;
  }
  const int64_t cpu_ns = thread_cpu_ns() - cpu_start;
  std::lock_guard lock(mutex_);
  copy_cpu_ns_ += cpu_ns;
}

double LiveImage::copy_cpu_seconds() const {
  std::lock_guard lock(mutex_);
  return double(copy_cpu_ns_) * 1e-9;
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
  s.frame = frame_;
  s.width = width_, s.height = height_;
  if (s.state == State::Loading && s.render == 0) return s;
  const bool running = status_.state == State::Rendering;
  s.elapsed = std::chrono::duration<double>((running ? Clock::now() : finished_) - started_).count();
  if (status_.state == State::Error || status_.state == State::Loading) s.elapsed = 0;
  const std::size_t pixels = rendered_.size();
  const int64_t done = std::min(done_, total_);
  s.samples_per_pixel = pixels > 0 ? double(taken_) / double(pixels) : 0;
  s.progress = s.state == State::Done ? 1.0 : double(done) / double(total_);
  if (running && done > 0) s.eta = s.elapsed * double(total_ - done) / double(done);
  if (s.state == State::Done) s.eta = 0.0;
  return s;
}

bool LiveImage::frame_since(uint64_t since, Frame& out) const {
  constexpr int kBandRows = 32;
  double scale;
  {
    std::lock_guard lock(mutex_);
    if (frame_ == since) return false;
    out.width = width_, out.height = height_, out.frame = frame_;
    scale = exposure_scale_;
  }
  const std::size_t n = std::size_t(out.width) * std::size_t(out.height);
  Sums& s = out.sums;
  s.sum.resize(3 * n), s.sum_sq.resize(3 * n), s.samples.resize(n);
  for (int y0 = 0; y0 < out.height; y0 += kBandRows) {
    std::lock_guard lock(mutex_);
    if (width_ != out.width || height_ != out.height) return false;  // a new render of another size began
    const std::size_t p0 = std::size_t(y0) * std::size_t(width_);
    const std::size_t p1 = std::size_t(std::min(y0 + kBandRows, height_)) * std::size_t(width_);
    std::copy(&sums_.sum[3 * p0], &sums_.sum[3 * p1], &s.sum[3 * p0]);
    std::copy(&sums_.sum_sq[3 * p0], &sums_.sum_sq[3 * p1], &s.sum_sq[3 * p0]);
    std::copy(&sums_.samples[p0], &sums_.samples[p1], &s.samples[p0]);
  }
  // The means and errors, off the lock.
  out.rgb.resize(3 * n), out.samples.resize(n), out.error.resize(n);
  for (std::size_t p = 0; p < n; ++p) {
    const uint32_t k = s.samples[p];
    for (int c = 0; c < 3; ++c) out.rgb[3 * p + c] = k > 0 ? float(s.sum[3 * p + c] / k * scale) : 0.0f;
    out.samples[p] = k;
    const float e = pixel_noise_error(&s.sum[3 * p], &s.sum_sq[3 * p], k, scale);
    out.error[p] = std::isfinite(e) ? e : -1.0f;
  }
  return true;
}

}  // namespace dermis
