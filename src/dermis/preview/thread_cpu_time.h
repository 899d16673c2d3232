// CPU time of threads (POSIX per-thread CPU clocks): what the live preview costs the render,
// measured on the threads that pay it rather than from the wall clock of a shared machine.
#pragma once

#include <pthread.h>
#include <time.h>

#include <cstdint>
#include <optional>

namespace dermis {

// The CPU nanoseconds a clock has counted (user and system time); -1 if it cannot be read
// (its thread has ended).
inline int64_t cpu_clock_ns(clockid_t clock) {
  timespec ts{};
  if (clock_gettime(clock, &ts) != 0) return -1;
  return int64_t(ts.tv_sec) * 1000000000 + ts.tv_nsec;
}

// The calling thread's CPU nanoseconds so far.
inline int64_t thread_cpu_ns() { return cpu_clock_ns(CLOCK_THREAD_CPUTIME_ID); }

// The calling thread's CPU clock, readable from other threads while it lives.
inline std::optional<clockid_t> this_thread_cpu_clock() {
  clockid_t clock{};
  if (pthread_getcpuclockid(pthread_self(), &clock) != 0) return std::nullopt;
  return clock;
}

}  // namespace dermis
