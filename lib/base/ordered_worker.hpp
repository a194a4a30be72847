// One worker thread that consumes items in the order they are pushed, with at most one item waiting:
// the producer makes item n + 1 while the worker handles item n (internal to the library). The GPU
// deformer hands read-back batches to the caller's sink this way, so that writing outputs overlaps the
// next dispatch, and render writes each image while the next one is drawn.
#pragma once

#include <condition_variable>
#include <exception>
#include <functional>
#include <mutex>
#include <optional>
#include <thread>

namespace dqskin::concurrency {

template <typename T>
class OrderedWorker {
public:
  explicit OrderedWorker(std::function<void(const T&)> consume)
      : consume_(std::move(consume)), thread_([this] { loop(); }) {}

  // Waits for the worker; an exception it threw is dropped here (call finish() to receive it).
  ~OrderedWorker() {
    {
      std::lock_guard lock(mutex_);
      closed_ = true;
    }
    changed_.notify_all();
    thread_.join();
  }

  OrderedWorker(const OrderedWorker&) = delete;
  OrderedWorker& operator=(const OrderedWorker&) = delete;

  // Queues `item` once the previous one has been taken. Rethrows the worker's exception, if any, after
  // which nothing more is consumed.
  void push(T item) {
    std::unique_lock lock(mutex_);
    changed_.wait(lock, [this] { return !waiting_ || error_; });
    if (error_) std::rethrow_exception(error_);
    waiting_ = std::move(item);
    changed_.notify_all();
  }

  // Waits until every pushed item has been consumed; rethrows the worker's exception, if any.
  void finish() {
    std::unique_lock lock(mutex_);
    changed_.wait(lock, [this] { return (!waiting_ && !busy_) || error_; });
    if (error_) std::rethrow_exception(error_);
  }

private:
  void loop() {
    for (;;) {
      std::optional<T> item;
      {
        std::unique_lock lock(mutex_);
        changed_.wait(lock, [this] { return waiting_ || closed_; });
        if (!waiting_ || error_) return;  // closed with nothing left, or stopped by an error
        item = std::move(waiting_);
        waiting_.reset();
        busy_ = true;
      }
      changed_.notify_all();
      std::exception_ptr error;
      try {
        consume_(*item);
      } catch (...) {
        error = std::current_exception();
      }
      {
        std::lock_guard lock(mutex_);
        busy_ = false;
        if (error && !error_) error_ = error;
      }
      changed_.notify_all();
    }
  }

  std::function<void(const T&)> consume_;
  std::mutex mutex_;
  std::condition_variable changed_;
  std::optional<T> waiting_;
  bool busy_ = false;
  bool closed_ = false;
  std::exception_ptr error_;
  std::thread thread_;  // last: starts after every other member exists
};

}  // namespace dqskin::concurrency
