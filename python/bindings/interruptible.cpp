#include "interruptible.h"

#include <chrono>
#include <exception>
#include <future>
#include <thread>

namespace py = pybind11;

namespace dermis::python {

std::optional<py::error_already_set> run_interruptible(const std::function<void()>& work, std::atomic<bool>& cancel,
                                                       const std::function<void()>& poll) {
  std::promise<void> finished;
  std::future<void> done = finished.get_future();
  std::exception_ptr failure;
  std::thread worker([&] {
    try {
      work();
    } catch (...) {
      failure = std::current_exception();
    }
    finished.set_value();
  });
  std::optional<py::error_already_set> python_error;
  while (true) {
    bool ready;
    {
      py::gil_scoped_release release;
      ready = done.wait_for(std::chrono::milliseconds(50)) == std::future_status::ready;
    }
    if (!python_error) {
      try {
        if (PyErr_CheckSignals() != 0) throw py::error_already_set();
        if (poll) poll();
      } catch (py::error_already_set& e) {
        python_error = std::move(e);
        cancel = true;
      }
    }
    if (ready) break;
  }
  worker.join();
  if (python_error) return python_error;  // work's failure then is most likely its being stopped
  if (failure) std::rethrow_exception(failure);
  return std::nullopt;
}

}  // namespace dermis::python
