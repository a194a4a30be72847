// Arithmetic on sizes that a file declares (internal to the estimates): sums and products that stop at
// the largest uint64_t instead of wrapping around, so that an absurd count makes an absurd estimate, never
// a small one.
#pragma once

#include <cstdint>
#include <limits>

namespace dqskin::saturating {

inline constexpr uint64_t kMax = std::numeric_limits<uint64_t>::max();

inline uint64_t add(uint64_t a, uint64_t b) { return a > kMax - b ? kMax : a + b; }
inline uint64_t mul(uint64_t a, uint64_t b) { return a != 0 && b > kMax / a ? kMax : a * b; }

}  // namespace dqskin::saturating
