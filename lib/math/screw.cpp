// Screw parameters of unit dual quaternions [Kenwright eq. 8-11; Kavan eq. 2; Pennestri eq. 7, 14-15].
#include "dqskin/dual_quat.hpp"

#include <cmath>
#include <limits>

namespace dqskin {

template <typename T>
Screw<T> to_screw(const DualQuat<T>& q) {
  const Vec3<T> v(q.real.x, q.real.y, q.real.z);
  const T s = glm::length(v);  // sin(θ/2)
  const T w = q.real.w;        // cos(θ/2)
  const Vec3<T> t = translation(q);

  Screw<T> screw;
  screw.theta = T(2) * std::atan2(s, w);  // [0, 2π], and exact near 0 where 2 acos(w) is not
  // Below ε² the vector part is rounding noise: call it a pure translation. (Above it, 1/s stays finite.)
  const T eps = std::numeric_limits<T>::epsilon();
  if (s <= eps * eps) {
    const T length = glm::length(t);
    screw.axis = length > T(0) ? t / length : Vec3<T>(0, 0, 1);
    screw.d = length;
    screw.moment = Vec3<T>(0);
    return screw;
  }
  screw.axis = v / s;
  screw.d = glm::dot(t, screw.axis);
  // The axis passes through p = ½ (t⊥ + cot(θ/2) l × t), so m = p × l = ½ (t × l + cot(θ/2) t⊥). This
  // form has no cancellation as θ → 0, unlike m = (v_d − (d/2) cos(θ/2) l) / sin(θ/2) [Kenwright eq. 11].
  const Vec3<T> t_perp = t - screw.d * screw.axis;
  screw.moment = T(0.5) * (glm::cross(t, screw.axis) + (w / s) * t_perp);
  return screw;
}

template <typename T>
DualQuat<T> from_screw(const Screw<T>& screw) {
  // [Kenwright eq. 10]: q = cos(θ̂/2) + (l + εm) sin(θ̂/2) expanded in its eight components.
  const T c = std::cos(screw.theta / T(2)), s = std::sin(screw.theta / T(2));
  const T half_d = screw.d / T(2);
  const Vec3<T> dual_v = s * screw.moment + (half_d * c) * screw.axis;
  return {Quat<T>(c, s * screw.axis), Quat<T>(-half_d * s, dual_v)};
}

template <typename T>
Vec3<T> point_on_axis(const Screw<T>& screw) {
  return glm::cross(screw.axis, screw.moment);  // l × (p × l) = p⊥, the foot of the perpendicular
}

template Screw<float> to_screw(const DualQuat<float>&);
template Screw<double> to_screw(const DualQuat<double>&);
template DualQuat<float> from_screw(const Screw<float>&);
template DualQuat<double> from_screw(const Screw<double>&);
template Vec3<float> point_on_axis(const Screw<float>&);
template Vec3<double> point_on_axis(const Screw<double>&);

}  // namespace dqskin
