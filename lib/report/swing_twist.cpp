#include "swing_twist.hpp"

#include <algorithm>
#include <cmath>

namespace dqskin::report_detail {

SwingTwist swing_twist(const Quat<double>& q, const glm::dvec3& axis) {
  const glm::dvec3 v(q.x, q.y, q.z);
  const double along = glm::dot(v, axis);
  double twist = glm::degrees(2.0 * std::atan2(along, q.w));
  while (twist > 180.0) twist -= 360.0;
  while (twist <= -180.0) twist += 360.0;
  // The twist quaternion (w, (v·a) a), normalised; when it vanishes (a half turn of pure swing) there is
  // no twist and the swing is q itself.
  const double norm = std::sqrt(q.w * q.w + along * along);
  Quat<double> swing = q;
  if (norm > 1e-12) {
    const Quat<double> t(q.w / norm, axis.x * along / norm, axis.y * along / norm, axis.z * along / norm);
    swing = q * glm::conjugate(t);
  }
  const double swing_deg = glm::degrees(2.0 * std::acos(std::clamp(std::abs(swing.w), 0.0, 1.0)));
  return {twist, swing_deg};
}

}  // namespace dqskin::report_detail
