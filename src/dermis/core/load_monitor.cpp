#include "dermis/core/load_monitor.h"

#include <algorithm>
#include <cmath>

namespace dermis {

LoadStage::LoadStage(const LoadMonitor* monitor, std::string name) : monitor_(monitor), name_(std::move(name)) {
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

}  // namespace dermis
