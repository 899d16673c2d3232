// `dermis render --watch`: the files a scene read, watched from a thread of its own. A
// change to any of them (its time or size, or it appears or goes) that then rests for
// kWatchDebounce is one change: a burst of saves restarts the render once. The watcher
// also forwards a stop signal to the render it may cancel.
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

namespace dermis::app {

inline constexpr std::chrono::milliseconds kWatchDebounce{300};

class SceneWatcher {
 public:
  // `cancel` is set when the files changed or `interrupted` is.
  SceneWatcher(const std::atomic<bool>& interrupted, std::atomic<bool>& cancel);
  ~SceneWatcher();
  SceneWatcher(const SceneWatcher&) = delete;
  SceneWatcher& operator=(const SceneWatcher&) = delete;

  // Watches these files from now on, as they are now (the scene just read), and clears a
  // change seen before and `cancel`.
  void watch(const std::vector<std::string>& files);
  // A change to the watched files has settled.
  bool changed() const { return changed_; }

 private:
  struct Stamp {
    std::string path;
    std::optional<std::filesystem::file_time_type> time;  // none: absent
    std::uintmax_t size = 0;
    bool operator==(const Stamp&) const = default;
  };
  static std::vector<Stamp> stamps(const std::vector<std::string>& files);
  void run();

  const std::atomic<bool>& interrupted_;
  std::atomic<bool>& cancel_;
  std::atomic<bool> changed_{false}, stop_{false};
  std::mutex mutex_;
  std::vector<std::string> files_;
  std::vector<Stamp> stamps_;
  uint64_t generation_ = 0;  // watch() calls: a burst seen before the last one is forgotten
  std::thread thread_;
};

}  // namespace dermis::app
