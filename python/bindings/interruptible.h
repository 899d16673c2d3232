// Long C++ work called from Python: it runs on its own thread while the calling thread
// waits without the GIL, waking every 50 ms to run Python's signal handlers (Ctrl-C
// raises KeyboardInterrupt there, and only there) and a poll (progress callbacks, which
// thus run on the calling thread).
#pragma once

#include <pybind11/pybind11.h>

#include <atomic>
#include <functional>
#include <optional>

namespace dermis::python {

// Runs `work` to its end. When a signal handler or `poll` raises, sets `cancel` (work
// should then stop soon) and returns that Python error once work has returned;
// otherwise returns nothing. An exception thrown by work is rethrown here (with the GIL).
std::optional<pybind11::error_already_set> run_interruptible(const std::function<void()>& work,
                                                             std::atomic<bool>& cancel,
                                                             const std::function<void()>& poll);

}  // namespace dermis::python
