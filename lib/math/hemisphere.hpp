// Antipodality helper shared by the interpolation and blending files (docs/DESIGN.md §3.5).
#pragma once

#include "dqskin/dual_quat.hpp"

namespace dqskin::detail {

// q or −q, whichever has a real part in the hemisphere of `pivot` (dot ≥ 0): the same pose, on the
// short way from pivot [Kavan §3, antipodality].
template <typename T>
DualQuat<T> in_hemisphere_of(const Quat<T>& pivot, const DualQuat<T>& q) {
  return glm::dot(pivot, q.real) < T(0) ? -q : q;
}

}  // namespace dqskin::detail
