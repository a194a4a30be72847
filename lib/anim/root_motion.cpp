// A root joint's motion on the ground, and the rigid matrices that put it back or take it out
// (docs/DESIGN.md §3.11).
#include "dqskin/animation.hpp"
#include "dqskin/dual_quat.hpp"

#include <cmath>

namespace dqskin {

GroundMotion ground_motion(const Mat4<double>& world) {
  // The twist about +Y of the rotation q (swing-twist decomposition q = twist · swing, the swing's axis in
  // the ground plane): twist = normalize(q.w, 0, q.y, 0), whose angle is 2 atan2(q.y, q.w). It does not
  // depend on which of the root's local axes points forward. nearest_rotation gives w ≥ 0, so the angle
  // lies in [-π, π]; when q.y = q.w = 0 (the root turned upside down) there is no heading and it is 0.
  const Quat<double> q = nearest_rotation(Mat3<double>(world));
  return {world[3].x, world[3].z, 2 * std::atan2(q.y, q.w)};
}

Mat4<double> ground_matrix(const GroundMotion& g) {
  const double c = std::cos(g.yaw), s = std::sin(g.yaw);
  Mat4<double> m(1.0);  // column-major: m[column][row]; Ry(yaw) maps x to (c, 0, -s) and z to (s, 0, c)
  m[0] = {c, 0, -s, 0};
  m[2] = {s, 0, c, 0};
  m[3] = {g.x, 0, g.z, 1};
  return m;
}

Mat4<double> ground_matrix_inverse(const GroundMotion& g) {
  // Ry(-yaw) · T(-x, 0, -z): the transposed rotation, and the translation turned by it.
  const double c = std::cos(g.yaw), s = std::sin(g.yaw);
  Mat4<double> m(1.0);
  m[0] = {c, 0, s, 0};
  m[2] = {-s, 0, c, 0};
  m[3] = {-(c * g.x - s * g.z), 0, -(s * g.x + c * g.z), 1};
  return m;
}

}  // namespace dqskin
