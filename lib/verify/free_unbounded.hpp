// Freeing JSON documents under --max-memory (internal to verify and merge). nlohmann frees a document's
// nested values through a vector it allocates (16 bytes a value), so that under a ceiling nearly reached,
// freeing a large document, in a destructor or while an exception unwinds, would throw std::bad_alloc out
// of a destructor and end the process (std::terminate) instead of printing the refusal. What holds a large
// document frees it through these.
#pragma once

#include "dqskin/memory_ceiling.hpp"

#include <utility>

namespace dqskin::verify_detail {

// Empties `value` (a document, or a container of them) with the ceiling lifted for as long as that takes.
template <class T>
void free_unbounded(T& value) noexcept {
  const MemoryCeilingLifted lifted;
  T freed{};
  using std::swap;
  swap(value, freed);
}  // `freed` is destroyed here, before `lifted`

// Frees `value` with free_unbounded when the scope ends, normally or by an exception.
template <class T>
class FreedUnbounded {
public:
  explicit FreedUnbounded(T& value) : value_(value) {}
  ~FreedUnbounded() { free_unbounded(value_); }
  FreedUnbounded(const FreedUnbounded&) = delete;
  FreedUnbounded& operator=(const FreedUnbounded&) = delete;

private:
  T& value_;
};

}  // namespace dqskin::verify_detail
