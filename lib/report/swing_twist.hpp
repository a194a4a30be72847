// The twist and bend of a joint (internal to lib/report): a rotation split into a twist about an axis and
// the swing that follows it (q = swing · twist), the usual swing–twist decomposition of a unit quaternion.
#pragma once

#include "dqskin/dual_quat.hpp"

namespace dqskin::report_detail {

struct SwingTwist {
  double twist_degrees = 0;  // about the axis, right-handed, wrapped to (−180, 180]
  double swing_degrees = 0;  // the angle of the swing, [0, 180]
};

// `q` a unit quaternion, `axis` a unit vector. twist = 2·atan2(v·a, w) (q = (w, v)), so that q and −q,
// the same rotation, give the same twist once wrapped; the swing is q · twist⁻¹, its angle 2·acos(|w|).
SwingTwist swing_twist(const Quat<double>& q, const glm::dvec3& axis);

}  // namespace dqskin::report_detail
