// The ceiling behind --max-memory: every operator new counted, an allocation past the ceiling refused
// before it is made (std::bad_alloc, or null for the nothrow forms), its message naming the figures, and
// the ceiling gone again where a failure is reported. The test binary links the counting allocator.
#include "dqskin/memory_ceiling.hpp"

#include "dqskin/error.hpp"
#include "../job/job_run.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <memory>
#include <new>
#include <thread>
#include <vector>

namespace dqskin {
namespace {

constexpr size_t kMiB = size_t(1) << 20;

// A heap block the optimizer cannot remove: a new whose result is never used may be elided
// ([expr.new]), so the pointer escapes into an asm statement that the compiler cannot see through.
std::unique_ptr<char[]> block(size_t bytes) {
  std::unique_ptr<char[]> p(new char[bytes]);
  asm volatile("" : : "g"(p.get()) : "memory");
  return p;
}

TEST(MemoryCeiling, CountsEveryBlockInAndOutAtItsSize) {
  ASSERT_TRUE(memory_counted());
  const uint64_t before = memory_in_use();
  {
    const auto p = block(3 * kMiB);
    EXPECT_GE(memory_in_use(), before + 3 * kMiB);
    EXPECT_GE(memory_peak(), before + 3 * kMiB);
  }
  EXPECT_EQ(memory_in_use(), before);
}

TEST(MemoryCeiling, RefusesAnAllocationThatWouldPassItBeforeMakingIt) {
  const uint64_t before = memory_in_use();
  const MemoryCeiling ceiling(4 * kMiB);
  const auto fits = block(3 * kMiB);
  EXPECT_THROW(block(2 * kMiB), std::bad_alloc);
  EXPECT_LT(memory_in_use(), before + 4 * kMiB);  // nothing of the refused block was counted
  EXPECT_EQ(out_of_memory_message(),
            "needs more memory than --max-memory 4.00 MiB allows (3.00 MiB in use, 2.00 MiB more asked for)");
}

TEST(MemoryCeiling, TheNothrowFormsReturnNull) {
  const MemoryCeiling ceiling(kMiB);
  char* p = new (std::nothrow) char[2 * kMiB];
  EXPECT_EQ(p, nullptr);
  delete[] p;
  static_cast<void>(out_of_memory_message());
}

// Frees its memory through an allocation, as nlohmann::json's destructor does (a stack as large as the
// array it destroys): without the exception below, a destructor run while a refusal unwinds would throw
// again and end the process.
struct AllocatesWhenDestroyed {
  ~AllocatesWhenDestroyed() { block(2 * kMiB); }
};

TEST(MemoryCeiling, DestructorsThatAllocateWhileARefusalUnwindsAreNotRefused) {
  const MemoryCeiling ceiling(4 * kMiB);
  const auto fits = block(3 * kMiB);
  bool caught = false;
  try {
    const AllocatesWhenDestroyed cleanup;
    block(2 * kMiB);  // refused: unwinding destroys `cleanup`, which allocates past the ceiling
  } catch (const std::bad_alloc&) {
    caught = true;
  }
  EXPECT_TRUE(caught);
  EXPECT_THROW(block(2 * kMiB), std::bad_alloc);  // outside unwinding the ceiling holds again
}

TEST(MemoryCeiling, WithoutARefusalTheMachineRanOut) {
  EXPECT_EQ(out_of_memory_message(), kOutOfMemory);
  {
    const MemoryCeiling ceiling(kMiB);
    EXPECT_THROW(block(2 * kMiB), std::bad_alloc);
  }
  EXPECT_NE(out_of_memory_message(), kOutOfMemory);
  EXPECT_EQ(out_of_memory_message(), kOutOfMemory) << "a refusal is told once";
}

TEST(MemoryCeiling, LiftedAndNestedCeilingsRestoreTheOneBefore) {
  const MemoryCeiling outer(2 * kMiB);
  {
    const MemoryCeilingLifted lifted;
    EXPECT_NO_THROW(block(8 * kMiB));
  }
  EXPECT_THROW(block(4 * kMiB), std::bad_alloc);
  {
    const MemoryCeiling inner(16 * kMiB);
    EXPECT_NO_THROW(block(8 * kMiB));
  }
  EXPECT_THROW(block(4 * kMiB), std::bad_alloc);
  static_cast<void>(out_of_memory_message());
}

TEST(MemoryCeiling, ThreadsThatAllocateAtOnceNeverPassItTogether) {
  // Four threads take 256 KiB blocks until refused, under a 4 MiB ceiling: the reservation is made before
  // malloc, so at most the ceiling is ever counted, and everything is counted out at the end.
  const uint64_t before = memory_in_use();
  std::atomic<uint64_t> highest{0};
  {
    const MemoryCeiling ceiling(4 * kMiB);
    std::vector<std::thread> threads;
    for (int t = 0; t < 4; ++t)
      threads.emplace_back([&] {
        std::vector<std::unique_ptr<char[]>> held;
        held.reserve(64);
        for (int i = 0; i < 64; ++i) {
          try {
            held.push_back(block(256 * 1024));
          } catch (const std::bad_alloc&) {
            break;
          }
          uint64_t now = memory_in_use(), seen = highest.load();
          while (now > seen && !highest.compare_exchange_weak(seen, now)) {
          }
        }
      });
    for (std::thread& t : threads) t.join();
  }
  EXPECT_LE(highest.load(), before + 4 * kMiB + 64 * 1024);  // the threads' own small allocations aside
  EXPECT_EQ(memory_in_use(), before);
  static_cast<void>(out_of_memory_message());
}

TEST(MemoryCeiling, AnInputPastTheCeilingFailsAloneWithTheFigures) {
  const MemoryCeiling ceiling(16 * kMiB);
  std::vector<InputPlan> plans(2);
  plans[0].path = "big.gltf", plans[1].path = "small.gltf";
  const std::vector<InputResult> results = for_each_input(
      plans,
      [](const InputPlan& input, OutputJournal&, InputResult&) {
        if (input.path == "big.gltf") static_cast<void>(block(64 * kMiB));
      },
      [](const InputPlan&) {});
  const std::string& error = results[0].error;
  EXPECT_EQ(error.rfind("needs more memory than --max-memory 16.0 MiB allows (", 0), 0u) << error;
  EXPECT_NE(error.find(" in use, 64.0 MiB more asked for)"), std::string::npos) << error;
  EXPECT_EQ(results[1].error, "");
}

}  // namespace
}  // namespace dqskin
