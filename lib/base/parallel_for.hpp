// Runs fn(0) … fn(n − 1) on up to `threads` threads (the caller's among them) and returns when all are
// done, rethrowing the first exception. Used for encoding the frames of one batch; threads are started
// per call, which costs microseconds against the milliseconds a frame takes to encode.
#pragma once

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace dqskin::concurrency {

template <class Fn>
void parallel_for(size_t n, unsigned threads, const Fn& fn) {
  std::atomic<size_t> next{0};
  std::exception_ptr error;
  std::mutex error_mutex;
  auto work = [&] {
    for (size_t i; (i = next++) < n;) {
      try {
        fn(i);
      } catch (...) {
        const std::lock_guard<std::mutex> lock(error_mutex);
        if (!error) error = std::current_exception();
        next = n;  // stop handing out work
      }
    }
  };
  std::vector<std::thread> helpers;
  const size_t extra = std::min<size_t>(n, std::max(1u, threads)) - (n > 0 ? 1 : 0);
  for (size_t t = 0; t < extra; ++t) helpers.emplace_back(work);
  work();
  for (std::thread& t : helpers) t.join();
  if (error) std::rethrow_exception(error);
}

}  // namespace dqskin::concurrency
