#include "dermis/core/load_monitor.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <thread>

namespace dermis {

namespace {

// Test-only (docs/testing.md): $DERMIS_TEST_LOAD_STEP_MS, read when a stage starts, pauses
// the stage that many milliseconds (at most 1000) after each report it makes: a stage that
// reports its 1 % steps then lasts at least a tenth of a second per millisecond asked, on any
// machine, so that a test that must see a stage running (its progress shown, Ctrl-C during
// it) does not depend on the machine's speed. Unset or not a positive number: no pause.
int test_step_pause_ms() {
  const char* env = std::getenv("DERMIS_TEST_LOAD_STEP_MS");
  const long ms = env ? std::strtol(env, nullptr, 10) : 0;
  return int(std::clamp(ms, 0L, 1000L));
}

}  // namespace

LoadStage::LoadStage(const LoadMonitor* monitor, std::string name)
    : monitor_(monitor), name_(std::move(name)), test_pause_ms_(test_step_pause_ms()) {
  throw_if_cancelled();
  report(0, true);
}

void LoadStage::update(double fraction) {
  throw_if_cancelled();
  report(fraction, false);
}

bool LoadStage::try_update(double fraction) noexcept {
  if (cancelled()) return false;
  report(fraction, false);
  return true;
}

void LoadStage::finish() {
  throw_if_cancelled();
  report(1, true);
}

void LoadStage::report(double fraction, bool force) noexcept {
  if (!monitor_ || !monitor_->progress) return;
  fraction = std::isfinite(fraction) ? std::clamp(fraction, 0.0, 1.0) : 0.0;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    // Non-decreasing: a late report from a slower thread is dropped.
    if (fraction < reported_ || (!force && fraction < reported_ + 0.01)) return;
    if (fraction == reported_ && fraction == 1) return;  // the end once
    reported_ = fraction;
    try {
      monitor_->progress(name_, fraction);
    } catch (...) {
      // A report cannot stop the load: the cancel flag does.
    }
  }
  if (test_pause_ms_ > 0) std::this_thread::sleep_for(std::chrono::milliseconds(test_pause_ms_));
}

}  // namespace dermis
