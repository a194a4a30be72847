// A budget of bytes shared by work that runs at once (internal to lib/diff): the pairs of a folder diff
// compared side by side under one --max-memory. Each piece of work states what it will hold before it
// allocates; it waits while that does not fit beside what the others hold, and runs at once when nothing
// else is held (work that alone fits the budget always runs, so waiting ends).
#pragma once

#include <condition_variable>
#include <cstdint>
#include <mutex>

namespace dqskin::diff_detail {

class MemoryLedger {
public:
  explicit MemoryLedger(uint64_t budget) : budget_(budget) {}

  // What a piece of work holds, given back when it ends.
  class Reservation {
  public:
    Reservation() = default;
    Reservation(MemoryLedger* ledger, uint64_t bytes) : ledger_(ledger), bytes_(bytes) {}
    Reservation(Reservation&& other) noexcept : ledger_(other.ledger_), bytes_(other.bytes_) { other.ledger_ = nullptr; }
    Reservation& operator=(Reservation&& other) noexcept {
      if (this != &other) {
        release();
        ledger_ = other.ledger_, bytes_ = other.bytes_;
        other.ledger_ = nullptr;
      }
      return *this;
    }
    Reservation(const Reservation&) = delete;
    Reservation& operator=(const Reservation&) = delete;
    ~Reservation() { release(); }

    void release() {
      if (ledger_) ledger_->give_back(bytes_);
      ledger_ = nullptr;
    }

  private:
    MemoryLedger* ledger_ = nullptr;
    uint64_t bytes_ = 0;
  };

  // Waits until `bytes` fit beside what is held (or nothing is held), then holds them.
  Reservation reserve(uint64_t bytes) {
    std::unique_lock<std::mutex> lock(mutex_);
    changed_.wait(lock, [&] { return held_ == 0 || (held_ <= budget_ && bytes <= budget_ - held_); });
    held_ += bytes;
    return Reservation(this, bytes);
  }

  uint64_t held() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return held_;
  }

private:
  void give_back(uint64_t bytes) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      held_ -= bytes;
    }
    changed_.notify_all();
  }

  const uint64_t budget_;
  uint64_t held_ = 0;
  mutable std::mutex mutex_;
  std::condition_variable changed_;
};

}  // namespace dqskin::diff_detail
