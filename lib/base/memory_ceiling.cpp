// The counters behind MemoryCeiling (dqskin/memory_ceiling.hpp). Lock-free: operator new calls reserve()
// from every thread, and the count must never allocate itself.
#include "dqskin/memory_ceiling.hpp"

#include "byte_size.hpp"
#include "dqskin/error.hpp"

#include <atomic>
#include <limits>

namespace dqskin {
namespace {

constexpr uint64_t kNoLimit = std::numeric_limits<uint64_t>::max();

std::atomic<uint64_t> g_in_use{0};
std::atomic<uint64_t> g_peak{0};
std::atomic<uint64_t> g_limit{kNoLimit};  // absolute: the base plus --max-memory
std::atomic<uint64_t> g_base{0};          // in use when the ceiling was set
std::atomic<bool> g_counted{false};

// The last refusal, for the message (written by the refusing thread; read after the exception unwound).
std::atomic<bool> g_refused{false};
std::atomic<uint64_t> g_refused_in_use{0}, g_refused_asked{0}, g_refused_ceiling{0};

void raise_peak(uint64_t now) noexcept {
  uint64_t peak = g_peak.load(std::memory_order_relaxed);
  while (now > peak && !g_peak.compare_exchange_weak(peak, now, std::memory_order_relaxed)) {
  }
}

}  // namespace

namespace memory_detail {

bool reserve(uint64_t bytes, bool always) noexcept {
  const uint64_t limit = g_limit.load(std::memory_order_relaxed);
  const uint64_t before = g_in_use.fetch_add(bytes, std::memory_order_relaxed);
  if (!always && limit != kNoLimit && (bytes > limit || before > limit - bytes)) {
    g_in_use.fetch_sub(bytes, std::memory_order_relaxed);
    const uint64_t base = g_base.load(std::memory_order_relaxed);
    g_refused_in_use.store(before > base ? before - base : 0, std::memory_order_relaxed);
    g_refused_asked.store(bytes, std::memory_order_relaxed);
    g_refused_ceiling.store(limit - base, std::memory_order_relaxed);
    g_refused.store(true, std::memory_order_release);
    return false;
  }
  raise_peak(before + bytes);
  return true;
}

void release(int64_t bytes) noexcept {
  if (bytes >= 0) {
    g_in_use.fetch_sub(uint64_t(bytes), std::memory_order_relaxed);
  } else {
    raise_peak(g_in_use.fetch_add(uint64_t(-bytes), std::memory_order_relaxed) + uint64_t(-bytes));
  }
}

void set_counted() noexcept { g_counted.store(true, std::memory_order_relaxed); }

}  // namespace memory_detail

MemoryCeiling::MemoryCeiling(uint64_t bytes)
    : previous_limit_(g_limit.load()), previous_base_(g_base.load()) {
  const uint64_t base = g_in_use.load();
  g_base = base;
  g_limit = bytes > kNoLimit - base - 1 ? kNoLimit - 1 : base + bytes;
  g_refused = false;
}

MemoryCeiling::~MemoryCeiling() {
  g_limit = previous_limit_;
  g_base = previous_base_;
}

MemoryCeilingLifted::MemoryCeilingLifted() : previous_limit_(g_limit.exchange(kNoLimit)) {}

MemoryCeilingLifted::~MemoryCeilingLifted() { g_limit = previous_limit_; }

bool memory_counted() { return g_counted.load(std::memory_order_relaxed); }

uint64_t memory_in_use() { return g_in_use.load(std::memory_order_relaxed); }

uint64_t memory_peak() { return g_peak.load(std::memory_order_relaxed); }

std::string out_of_memory_message() {
  if (!g_refused.exchange(false, std::memory_order_acquire)) return kOutOfMemory;
  const MemoryCeilingLifted lifted;  // the message itself allocates
  return "needs more memory than --max-memory " + byte_size(g_refused_ceiling.load()) + " allows (" +
         byte_size(g_refused_in_use.load()) + " in use, " + byte_size(g_refused_asked.load()) + " more asked for)";
}

}  // namespace dqskin
