// Progress reporting for long loops run on many threads: a one-line bar on a
// terminal, plain lines in a log, nothing in tests.
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <mutex>
#include <string>

namespace dermis {

// "3.2s", "42s", "1m 05s", "2h 03m 04s"; "--" for a negative or non-finite time.
std::string format_duration(double seconds);

// Remaining time by linear extrapolation of the rate so far; negative when unknown
// (nothing done yet).
double estimate_remaining_seconds(double elapsed_seconds, int64_t done, int64_t total);

// Fraction done in [0, 1]; an empty job (total <= 0) counts as complete.
double progress_fraction(int64_t done, int64_t total);

// "label [##########          ]  50.0%  1m 05s elapsed, ETA 1m 05s"
std::string format_progress_bar(const std::string& label, int64_t done, int64_t total, double elapsed_seconds,
                                int bar_width = 30);
// "label: 50% (500/1000), 1m 05s elapsed, ETA 1m 05s"
std::string format_progress_line(const std::string& label, int64_t done, int64_t total, double elapsed_seconds);

class Progress {
 public:
  // kAuto: kBar when `out` is a terminal, kLines otherwise.
  enum class Style { kAuto, kBar, kLines, kQuiet };

  Progress(std::string label, int64_t total, Style style = Style::kAuto, std::FILE* out = stderr);
  ~Progress();
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  // Adds n units of work done. Safe and cheap from any number of threads: one atomic
  // add and a clock read; whichever thread first passes the next redraw time (at most
  // 10 per second), or in line mode crosses a 10% step, draws, if nobody else is drawing.
  void advance(int64_t n = 1);
  // A few words shown after the bar or line from the next redraw on (e.g. "62% of pixels
  // converged"); empty: none.
  void set_note(std::string note);
  // Draws the final state (bar: ends the line; lines: "label: done in ..."). Idempotent.
  void finish();

  int64_t done() const { return done_.load(std::memory_order_relaxed); }
  int64_t total() const { return total_; }
  Style style() const { return style_; }
  double elapsed_seconds() const;

 private:
  int64_t now_ns() const;
  int decile(int64_t done) const;
  void draw(int64_t t_ns, bool final);  // with draw_mutex_ held

  std::string label_;
  int64_t total_;
  Style style_;
  std::FILE* out_;
  std::chrono::steady_clock::time_point start_;
  std::atomic<int64_t> done_{0};
  std::atomic<int64_t> next_redraw_ns_{0};
  std::atomic<bool> finished_{false};
  std::mutex draw_mutex_;
  // Guarded by draw_mutex_.
  int last_decile_ = 0;
  int64_t last_line_ns_ = 0;
  std::size_t last_bar_length_ = 0;
  std::string note_;
};

}  // namespace dermis
