#include "dermis/render/progress.h"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>

namespace dermis {

namespace {
constexpr int64_t kRedrawIntervalNs = 100'000'000;   // at most 10 redraws a second
constexpr int64_t kLineIntervalNs = 10'000'000'000;  // in line mode, a line at least every 10 s
}  // namespace

std::string format_duration(double seconds) {
  if (!std::isfinite(seconds) || seconds < 0) return "--";
  if (seconds < 9.95) return fmt::format("{:.1f}s", seconds);
  const long long s = std::llround(seconds);
  if (s < 60) return fmt::format("{}s", s);
  if (s < 3600) return fmt::format("{}m {:02}s", s / 60, s % 60);
  return fmt::format("{}h {:02}m {:02}s", s / 3600, (s / 60) % 60, s % 60);
}

double estimate_remaining_seconds(double elapsed_seconds, int64_t done, int64_t total) {
  if (done <= 0) return -1;
  if (done >= total) return 0;
  return elapsed_seconds * double(total - done) / double(done);
}

double progress_fraction(int64_t done, int64_t total) {
  if (total <= 0) return 1;
  return std::clamp(double(done) / double(total), 0.0, 1.0);
}

std::string format_progress_bar(const std::string& label, int64_t done, int64_t total, double elapsed_seconds,
                                int bar_width) {
  const double f = progress_fraction(done, total);
  const int filled = std::clamp(int(f * bar_width), 0, bar_width);
  return fmt::format("{} [{}{}] {:5.1f}%  {} elapsed, ETA {}", label, std::string(std::size_t(filled), '#'),
                     std::string(std::size_t(bar_width - filled), ' '), 100 * f, format_duration(elapsed_seconds),
                     format_duration(estimate_remaining_seconds(elapsed_seconds, done, total)));
}

std::string format_progress_line(const std::string& label, int64_t done, int64_t total, double elapsed_seconds) {
  return fmt::format("{}: {:.0f}% ({}/{}), {} elapsed, ETA {}", label, 100 * progress_fraction(done, total), done,
                     total, format_duration(elapsed_seconds),
                     format_duration(estimate_remaining_seconds(elapsed_seconds, done, total)));
}

Progress::Progress(std::string label, int64_t total, Style style, std::FILE* out)
    : label_(std::move(label)), total_(total), style_(style), out_(out), start_(std::chrono::steady_clock::now()) {
  if (style_ == Style::kAuto) style_ = (out_ && ::isatty(::fileno(out_))) ? Style::kBar : Style::kLines;
  if (!out_) style_ = Style::kQuiet;
}

Progress::~Progress() {
  // Abandoned (e.g. by an exception): do not claim completion, but end the bar's line.
  if (style_ == Style::kBar && !finished_.load() && last_bar_length_ > 0) {
    std::lock_guard lock(draw_mutex_);
    std::fputc('\n', out_);
    std::fflush(out_);
  }
}

int64_t Progress::now_ns() const {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now() - start_).count();
}

double Progress::elapsed_seconds() const { return double(now_ns()) * 1e-9; }

int Progress::decile(int64_t done) const { return std::min(10, int(10 * progress_fraction(done, total_))); }

void Progress::advance(int64_t n) {
  const int64_t before = done_.fetch_add(n, std::memory_order_relaxed);
  if (style_ == Style::kQuiet) return;
  const int64_t t = now_ns();
  const bool step_crossed = style_ == Style::kLines && decile(before) != decile(before + n);
  if (!step_crossed && t < next_redraw_ns_.load(std::memory_order_relaxed)) return;
  std::unique_lock lock(draw_mutex_, std::try_to_lock);
  if (!lock.owns_lock() || finished_.load()) return;  // someone else is drawing
  draw(t, false);
}

void Progress::set_note(std::string note) {
  std::lock_guard lock(draw_mutex_);
  note_ = std::move(note);
}

void Progress::finish() {
  if (finished_.exchange(true)) return;
  if (style_ == Style::kQuiet) return;
  std::lock_guard lock(draw_mutex_);
  draw(now_ns(), true);
}

void Progress::draw(int64_t t, bool final) {
  next_redraw_ns_.store(t + kRedrawIntervalNs, std::memory_order_relaxed);
  // A job may learn of work it need not do after counting some of it twice (adaptive
  // sampling): never more than the total is shown.
  const int64_t done =
      total_ > 0 ? std::min(done_.load(std::memory_order_relaxed), total_) : done_.load(std::memory_order_relaxed);
  const double elapsed = double(t) * 1e-9;
  if (style_ == Style::kBar) {
    std::string bar = format_progress_bar(label_, done, total_, elapsed);
    if (!note_.empty()) bar += ", " + note_;
    const std::size_t length = bar.size();
    // Blank out the tail of a longer previous bar.
    if (length < last_bar_length_) bar.append(last_bar_length_ - length, ' ');
    last_bar_length_ = length;
    std::fputc('\r', out_);
    std::fputs(bar.c_str(), out_);
    if (final) std::fputc('\n', out_);
  } else if (style_ == Style::kLines) {
    if (final) {
      std::fputs(fmt::format("{}: done ({}/{}) in {}{}\n", label_, done, total_, format_duration(elapsed),
                             note_.empty() ? "" : ", " + note_)
                     .c_str(),
                 out_);
    } else {
      const int d = decile(done);
      if (d <= last_decile_ && t - last_line_ns_ < kLineIntervalNs) return;
      last_decile_ = std::max(last_decile_, d);
      last_line_ns_ = t;
      std::fputs(
          (format_progress_line(label_, done, total_, elapsed) + (note_.empty() ? "" : ", " + note_) + "\n").c_str(),
          out_);
    }
  }
  std::fflush(out_);
}

}  // namespace dermis
