// --max-memory as a ceiling on what a command holds, whatever allocates it: the loader, the deformers,
// the encoders, the reports and the libraries behind them (docs/SECURITY.md, "What dqskin reads").
//
// Every operator new of the process is counted when the binary links the counting allocator
// (lib/base/counting_new.cpp, in the dqskin command line; not in the library, so that an application
// linking dqskin keeps its own allocator). Under a ceiling, an allocation that would take the bytes in
// use past it throws std::bad_alloc before anything is allocated, so the limit holds for every allocation
// that grows with the input, not only for those an estimate foresaw. Memory that C libraries take with
// malloc (libpng, zlib, the GL driver) is not counted: what they decode is bounded by the sizes checked
// before they are called.
//
// The estimates before each step (the loader's, the frame's) stay: they refuse most inputs at once with
// the step's own figures; the ceiling is what makes the promise hold when an estimate falls short.
#pragma once

#include <cstdint>
#include <string>

namespace dqskin {

// From construction to destruction, allocations may take at most `bytes` more than were in use at
// construction (what the process held before the command: its libraries' tables, the parsed command
// line). Ceilings nest; the destructor restores the one before. Not thread-safe against other ceilings:
// the command line sets one per command, before any work starts.
class MemoryCeiling {
public:
  explicit MemoryCeiling(uint64_t bytes);
  ~MemoryCeiling();
  MemoryCeiling(const MemoryCeiling&) = delete;
  MemoryCeiling& operator=(const MemoryCeiling&) = delete;

private:
  uint64_t previous_limit_, previous_base_;
};

// Lifts the ceiling while in scope, for what runs after a refusal: the message, taking back a failed
// input's files. The failed step's memory is freed by then (the exception unwound it), so what this lets
// through is small. Restores the ceiling, as it was, on destruction.
class MemoryCeilingLifted {
public:
  MemoryCeilingLifted();
  ~MemoryCeilingLifted();
  MemoryCeilingLifted(const MemoryCeilingLifted&) = delete;
  MemoryCeilingLifted& operator=(const MemoryCeilingLifted&) = delete;

private:
  uint64_t previous_limit_;
};

// Whether this binary counts its allocations (links the counting allocator). Without it the ceiling
// refuses nothing and memory_in_use() is 0.
bool memory_counted();

// Bytes allocated with operator new and not yet freed, as malloc rounds them.
uint64_t memory_in_use();

// The most memory_in_use() has been since the process started.
uint64_t memory_peak();

// The message for a std::bad_alloc caught at an input's or a command's boundary, which the caller
// prefixes with the file: when the ceiling refused the allocation, how much was in use and asked for
// against --max-memory ("needs more memory than --max-memory 256 MiB allows: 250 MiB in use, 12.0 MiB
// more asked for"); otherwise kOutOfMemory (the machine itself ran out). Forgets the refusal, so that the
// next input's message is its own.
std::string out_of_memory_message();

// What lib/base/counting_new.cpp calls; nothing else should.
namespace memory_detail {
// Counts `bytes` about to be allocated; false (nothing counted) when they would pass the ceiling, unless
// `always` (then they are counted whatever the ceiling).
bool reserve(uint64_t bytes, bool always = false) noexcept;
// Counts `bytes` freed, or reserved and not allocated after all (negative: more were allocated).
void release(int64_t bytes) noexcept;
// Marks the binary as counting (counting_new.cpp does, as it is initialized).
void set_counted() noexcept;
}  // namespace memory_detail

}  // namespace dqskin
