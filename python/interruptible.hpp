// Long calls that Ctrl-C stops (internal to the Python module). The work runs on a thread of its own with
// the GIL released, so other Python threads run meanwhile; the calling thread waits in steps of 50 ms and
// lets Python run its signal handlers each time. When one raises (KeyboardInterrupt), the work's cancel
// flag is set, the work stops at its next cancellation point (a batch of frames), and the Python exception
// is raised: within a second of Ctrl-C.
#pragma once

#include <atomic>
#include <functional>
#include <optional>

namespace dqskin::python {

// Runs work(cancel) as above. Rethrows the work's exception in the caller (for pybind11 to translate), or
// throws pybind11::error_already_set when a signal handler raised. Called with the GIL held.
void run_interruptible(const std::function<void(const std::atomic<bool>& cancel)>& work);

// The same for work that returns a value.
template <class T, class Fn>
T run_interruptible_for(Fn&& work) {
  std::optional<T> result;
  run_interruptible([&](const std::atomic<bool>& cancel) { result.emplace(work(cancel)); });
  return std::move(*result);
}

}  // namespace dqskin::python
