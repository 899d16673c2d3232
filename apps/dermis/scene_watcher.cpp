#include "scene_watcher.h"

#include <algorithm>

namespace dermis::app {

namespace {
constexpr std::chrono::milliseconds kPoll{50};
}

SceneWatcher::SceneWatcher(const std::atomic<bool>& interrupted, std::atomic<bool>& cancel)
    : interrupted_(interrupted), cancel_(cancel), thread_([this] { run(); }) {}

SceneWatcher::~SceneWatcher() {
  stop_ = true;
  thread_.join();
}

std::vector<SceneWatcher::Stamp> SceneWatcher::stamps(const std::vector<std::string>& files) {
  std::vector<Stamp> out;
  for (const std::string& f : files) {
    Stamp s{f, std::nullopt, 0};
    std::error_code ec;
    const auto time = std::filesystem::last_write_time(f, ec);
    if (!ec) {
      s.time = time;
      s.size = std::filesystem::file_size(f, ec);
      if (ec) s.size = 0;  // a directory, or gone since
    }
    out.push_back(std::move(s));
  }
  return out;
}

void SceneWatcher::watch(const std::vector<std::string>& files) {
  std::vector<std::string> unique = files;
  std::sort(unique.begin(), unique.end());
  unique.erase(std::unique(unique.begin(), unique.end()), unique.end());
  std::vector<Stamp> now = stamps(unique);
  std::lock_guard lock(mutex_);
  files_ = std::move(unique);
  stamps_ = std::move(now);
  ++generation_;
  changed_ = false;
  cancel_ = false;
}

void SceneWatcher::run() {
  using Clock = std::chrono::steady_clock;
  bool in_burst = false;
  Clock::time_point last_change{};  // in the burst under way
  std::vector<Stamp> seen;          // the files as the burst left them so far
  uint64_t generation = 0;
  while (!stop_) {
    std::this_thread::sleep_for(kPoll);
    if (interrupted_) cancel_ = true;
    if (changed_) continue;
    std::vector<std::string> files;
    std::vector<Stamp> reference;
    {
      std::lock_guard lock(mutex_);
      if (generation != generation_) generation = generation_, in_burst = false;
      files = files_;
      reference = in_burst ? seen : stamps_;
    }
    if (files.empty()) continue;
    std::vector<Stamp> now = stamps(files);
    if (now != reference) {
      in_burst = true;
      last_change = Clock::now();
      seen = std::move(now);
    } else if (in_burst && Clock::now() - last_change >= kWatchDebounce) {
      in_burst = false;
      std::lock_guard lock(mutex_);
      if (generation == generation_) changed_ = true, cancel_ = true;  // else watch() came in between
    }
  }
}

}  // namespace dermis::app
