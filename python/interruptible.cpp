#include "interruptible.hpp"

#include <pybind11/pybind11.h>

#include <chrono>
#include <exception>
#include <future>
#include <thread>

namespace dqskin::python {

namespace py = pybind11;

void run_interruptible(const std::function<void(const std::atomic<bool>& cancel)>& work) {
  std::atomic<bool> cancel{false};
  std::promise<void> done;
  std::future<void> finished = done.get_future();
  std::thread worker([&] {
    try {
      work(cancel);
      done.set_value();
    } catch (...) {
      done.set_exception(std::current_exception());
    }
  });
  bool interrupted = false;
  for (;;) {
    std::future_status status;
    {
      py::gil_scoped_release released;
      status = finished.wait_for(std::chrono::milliseconds(50));
    }
    if (status == std::future_status::ready) break;
    if (!interrupted && PyErr_CheckSignals() != 0) {
      interrupted = true;  // the Python error stays set until raised below
      cancel = true;
    }
  }
  {
    py::gil_scoped_release released;
    worker.join();
  }
  if (interrupted) {
    try {
      finished.get();  // the work stopped (JobCancelled) or finished first: either way Python's error wins
    } catch (...) {
    }
    throw py::error_already_set();
  }
  finished.get();
}

}  // namespace dqskin::python
