// Progress and Ctrl-C while a scene loads: reading and inflating files, parsing meshes,
// subdividing surfaces, building the BVH. The caller (the command line, the Python
// module) passes a LoadMonitor down; each long step is a LoadStage that reports how far
// it is and stops, throwing Interrupted, once the monitor's cancel flag is set.
#pragma once

#include <atomic>
#include <functional>
#include <mutex>
#include <stdexcept>
#include <string>

namespace dermis {

// Thrown by work stopped by its cancel flag (loading, preparation, the point clouds).
struct Interrupted : std::runtime_error {
  Interrupted() : std::runtime_error("interrupted") {}
};

struct LoadMonitor {
  // Called with a stage's name ("reading bust.ply", "building the BVH") and the fraction
  // of it done: 0 when it starts, non-decreasing, 1 when it ends. Calls come one at a
  // time, from the loading thread or from the BVH builder's threads. May be empty.
  std::function<void(const std::string& stage, double fraction)> progress;
  const std::atomic<bool>* cancel = nullptr;  // set (e.g. by SIGINT) to stop: throws Interrupted

  bool cancelled() const { return cancel && cancel->load(std::memory_order_relaxed); }
};

// One stage of a load, reported to a monitor (null: none; every call is then a no-op).
class LoadStage {
 public:
  // Reports 0 (and throws Interrupted if cancel is already set).
  LoadStage(const LoadMonitor* monitor, std::string name);
  LoadStage(const LoadStage&) = delete;
  LoadStage& operator=(const LoadStage&) = delete;

  // `fraction` of the stage done (clamped to [0, 1]); reported when it has grown by at
  // least 1% since the last report, so that calling it often costs little. Throws
  // Interrupted when the cancel flag is set. Safe from several threads.
  void update(double fraction);
  // As update, for callers that must not throw (Embree's progress callback): returns
  // false instead when the cancel flag is set.
  bool try_update(double fraction) noexcept;
  // Reports 1. Throws Interrupted when the cancel flag is set.
  void finish();

  bool cancelled() const { return monitor_ && monitor_->cancelled(); }
  void throw_if_cancelled() const {
    if (cancelled()) throw Interrupted();
  }

 private:
  void report(double fraction, bool force) noexcept;

  const LoadMonitor* monitor_;
  std::string name_;
  std::mutex mutex_;
  double reported_ = -1;   // guarded by mutex_
  int test_pause_ms_ = 0;  // $DERMIS_TEST_LOAD_STEP_MS (load_monitor.cpp): tests only
};

}  // namespace dermis
