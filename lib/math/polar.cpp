// Split of a non-rigid joint matrix [A | t] into a rigid part [R | t] and a symmetric S with A = R S
// (docs/DESIGN.md §3.6; Kavan et al. 2008, two-phase skinning: S is blended linearly,
// the rigid parts with DLB).
#include "dqskin/dual_quat.hpp"

#include <cmath>

namespace dqskin {

template <typename T>
JointSplit<T> split_joint_matrix(const Mat4<T>& m, T tolerance) {
  const Mat3<T> a(m);
  const Quat<T> r = nearest_rotation(a);
  // S = Rᵀ A is symmetric for the trace-maximising R (A = U Σ Vᵀ, R = U D Vᵀ ⇒ Rᵀ A = V D Σ Vᵀ); average
  // with its transpose to drop the rounding.
  const Mat3<T> raw = glm::transpose(glm::mat3_cast(r)) * a;
  const Mat3<T> s = (raw + glm::transpose(raw)) * T(0.5);

  bool rigid = true;
  for (int c = 0; c < 3; ++c)
    for (int k = 0; k < 3; ++k) rigid = rigid && std::abs(s[c][k] - (c == k ? T(1) : T(0))) <= tolerance;

  return {from_rotation_translation(r, Vec3<T>(m[3])), rigid ? Mat3<T>(T(1)) : s, rigid};
}

template JointSplit<float> split_joint_matrix(const Mat4<float>&, float);
template JointSplit<double> split_joint_matrix(const Mat4<double>&, double);

}  // namespace dqskin
