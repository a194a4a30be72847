// Blending of n rigid poses: DLB and DIB [Kavan §4; Pennestri §5.2-5.3], QLB for rotations and the linear
// blend of matrices (LBS) that skinning compares against [Kavan §6].
#include "dqskin/dual_quat.hpp"
#include "hemisphere.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>

namespace dqskin {
namespace {

template <typename T>
size_t largest_weight(std::span<const T> w) {
  return size_t(std::max_element(w.begin(), w.end()) - w.begin());
}

template <typename T>
T magnitude(const DualVec<T>& x) {
  return std::max(glm::length(x.real), glm::length(x.dual));
}

}  // namespace

template <typename T>
DualQuat<T> blend_dlb(std::span<const DualQuat<T>> q, std::span<const T> w) {
  assert(!q.empty() && q.size() == w.size());
  const Quat<T> pivot = q[largest_weight(w)].real;
  DualQuat<T> sum(Quat<T>(0, 0, 0, 0), Quat<T>(0, 0, 0, 0));
  for (size_t i = 0; i < q.size(); ++i) sum = sum + detail::in_hemisphere_of(pivot, q[i]) * w[i];
  return normalize(sum);  // [Kavan §4; Pennestri eq. 33]
}

template <typename T>
DibResult<T> blend_dib(std::span<const DualQuat<T>> q, std::span<const T> w, const DibOptions& options) {
  assert(!q.empty() && q.size() == w.size());
  // A precision below the type's rounding could never be met; hold it at 16 ulps of 1.
  const T precision = std::max(T(options.precision), T(16) * std::numeric_limits<T>::epsilon());
  T weight_sum = 0;
  for (T x : w) weight_sum += x;
  const T scale = weight_sum != T(0) ? T(1) / weight_sum : T(1);

  // [Kavan §4, DIB box; Pennestri Alg. 3]
  DibResult<T> result{blend_dlb(q, w), 0, false};
  for (;;) {
    const DualQuat<T> inverse_b = quat_conjugate(result.blend);
    DualVec<T> x;
    for (size_t i = 0; i < q.size(); ++i) {
      // b* qᵢ on its short side, so its logarithm has rotation angle ≤ π.
      const DualVec<T> xi = log(detail::in_hemisphere_of(Quat<T>(1, 0, 0, 0), inverse_b * q[i]));
      x.real += xi.real * (w[i] * scale);
      x.dual += xi.dual * (w[i] * scale);
    }
    if (magnitude(x) < precision) {
      result.converged = true;
      return result;
    }
    if (result.iterations >= options.max_iterations) return result;
    // exp(x) is unit, so b exp(x) is too but for rounding; normalize keeps the drift out.
    result.blend = normalize(result.blend * exp(x));
    ++result.iterations;
  }
}

template <typename T>
Quat<T> blend_qlb(std::span<const Quat<T>> q, std::span<const T> w) {
  assert(!q.empty() && q.size() == w.size());
  const Quat<T> pivot = q[largest_weight(w)];
  Quat<T> sum(0, 0, 0, 0);
  for (size_t i = 0; i < q.size(); ++i) sum = sum + (glm::dot(pivot, q[i]) < T(0) ? -q[i] : q[i]) * w[i];
  return glm::normalize(sum);
}

template <typename T>
Mat4<T> blend_lbs(std::span<const Mat4<T>> m, std::span<const T> w) {
  assert(!m.empty() && m.size() == w.size());
  Mat4<T> sum = m[0] * w[0];  // not a zero matrix plus: GCC then vectorises badly across the inputs
  for (size_t i = 1; i < m.size(); ++i) sum += m[i] * w[i];
  return sum;
}

#define DQSKIN_INSTANTIATE(T)                                                                          \
  template DualQuat<T> blend_dlb(std::span<const DualQuat<T>>, std::span<const T>);                    \
  template DibResult<T> blend_dib(std::span<const DualQuat<T>>, std::span<const T>, const DibOptions&); \
  template Quat<T> blend_qlb(std::span<const Quat<T>>, std::span<const T>);                            \
  template Mat4<T> blend_lbs(std::span<const Mat4<T>>, std::span<const T>);
DQSKIN_INSTANTIATE(float)
DQSKIN_INSTANTIATE(double)
#undef DQSKIN_INSTANTIATE

}  // namespace dqskin
