// The ledger of bytes that pairs compared at once share: work waits while it does not fit beside what is
// held, and runs at once when nothing is held, whatever its size.
#include "memory_ledger.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <thread>

namespace dqskin::diff_detail {
namespace {

using namespace std::chrono_literals;

TEST(MemoryLedger, HoldsUntilReleased) {
  MemoryLedger ledger(100);
  {
    MemoryLedger::Reservation a = ledger.reserve(60);
    MemoryLedger::Reservation b = ledger.reserve(40);  // fits exactly beside a
    EXPECT_EQ(ledger.held(), 100u);
    b.release();
    EXPECT_EQ(ledger.held(), 60u);
  }
  EXPECT_EQ(ledger.held(), 0u);
}

TEST(MemoryLedger, WorkOverTheBudgetRunsAloneRatherThanNever) {
  MemoryLedger ledger(100);
  MemoryLedger::Reservation big = ledger.reserve(150);
  EXPECT_EQ(ledger.held(), 150u);
}

TEST(MemoryLedger, WaitsWhileTheOthersHoldTooMuch) {
  MemoryLedger ledger(100);
  MemoryLedger::Reservation first = ledger.reserve(70);
  std::atomic<bool> got{false};
  std::thread second([&] {
    MemoryLedger::Reservation r = ledger.reserve(50);
    got = true;
  });
  std::this_thread::sleep_for(50ms);
  EXPECT_FALSE(got) << "50 bytes beside 70 of a budget of 100 must wait";
  first.release();
  second.join();
  EXPECT_TRUE(got);
  EXPECT_EQ(ledger.held(), 0u);
}

TEST(MemoryLedger, AMovedReservationIsGivenBackOnce) {
  MemoryLedger ledger(100);
  MemoryLedger::Reservation a = ledger.reserve(30);
  MemoryLedger::Reservation b = std::move(a);
  a.release();  // holds nothing now
  EXPECT_EQ(ledger.held(), 30u);
  b = ledger.reserve(20);  // the 30 given back as b takes the 20
  EXPECT_EQ(ledger.held(), 20u);
}

}  // namespace
}  // namespace dqskin::diff_detail
