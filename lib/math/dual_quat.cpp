// Dual-quaternion algebra and conversions [Kavan §3; Pennestri §2-3 and appendix; Kenwright §2].
#include "dqskin/dual_quat.hpp"

#include <cmath>

namespace dqskin {

template <typename T>
DualQuat<T> identity() {
  return glm::dual_quat_identity<T, glm::defaultp>();
}

template <typename T>
DualQuat<T> quat_conjugate(const DualQuat<T>& q) {
  return {glm::conjugate(q.real), glm::conjugate(q.dual)};
}

template <typename T>
DualQuat<T> dual_conjugate(const DualQuat<T>& q) {
  return {q.real, -q.dual};
}

template <typename T>
DualQuat<T> full_conjugate(const DualQuat<T>& q) {
  return {glm::conjugate(q.real), -glm::conjugate(q.dual)};
}

template <typename T>
Dual<T> norm(const DualQuat<T>& q) {
  // ||q|| = |r| + ε <r, d> / |r|  [Kavan §3]
  const T length = glm::length(q.real);
  return {length, glm::dot(q.real, q.dual) / length};
}

template <typename T>
DualQuat<T> normalize(const DualQuat<T>& q) {
  // Division by the dual number a + εb: (r + εd) / (a + εb) = r/a + ε (d/a − r b/a²).
  const Dual<T> n = norm(q);
  const T inv = T(1) / n.real;
  return {q.real * inv, (q.dual - q.real * (n.dual * inv)) * inv};
}

template <typename T>
DualQuat<T> inverse(const DualQuat<T>& q) {
  // q⁻¹ = q* / ||q||², with ||q||² = |r|² + ε 2<r, d> as a dual number  [Kavan §3; Pennestri eq. 43].
  const T a = glm::dot(q.real, q.real);
  const T b = T(2) * glm::dot(q.real, q.dual);
  const DualQuat<T> c = quat_conjugate(q);
  return {c.real / a, c.dual / a - c.real * (b / (a * a))};
}

template <typename T>
bool is_unit(const DualQuat<T>& q, T tolerance) {
  const Dual<T> n = norm(q);
  return std::abs(n.real - T(1)) <= tolerance && std::abs(n.dual) <= tolerance;
}

template <typename T>
DualQuat<T> from_rotation_translation(const Quat<T>& r, const Vec3<T>& t) {
  return DualQuat<T>(r, t);  // GLM builds dual = 0.5 (0, t) r  [Kavan eq. 1]
}

template <typename T>
Vec3<T> translation(const DualQuat<T>& q) {
  const Quat<T> t = (q.dual * glm::conjugate(q.real)) * T(2);  // [Kavan §3]
  return {t.x, t.y, t.z};
}

template <typename T>
DualQuat<T> from_rigid_matrix(const Mat4<T>& m) {
  Quat<T> r = glm::normalize(glm::quat_cast(Mat3<T>(m)));
  if (r.w < T(0)) r = -r;  // one fixed sign, so equal matrices give equal bits
  return from_rotation_translation(r, Vec3<T>(m[3]));
}

template <typename T>
Mat4<T> to_rigid_matrix(const DualQuat<T>& q) {
  Mat4<T> m(glm::mat3_cast(q.real));
  m[3] = glm::vec<4, T, glm::defaultp>(translation(q), T(1));
  return m;
}

template <typename T>
Vec3<T> transform_point(const DualQuat<T>& q, const Vec3<T>& p) {
  return q * p;  // GLM expands q (1 + εp) q† for the (r, 0.5 t r) convention
}

template <typename T>
Vec3<T> rotate_vector(const DualQuat<T>& q, const Vec3<T>& v) {
  return q.real * v;
}

template <typename T>
DualMat3<T> line_transform(const DualQuat<T>& q) {
  // [Â] = R + ε [t]× R  [Pennestri eq. 21]: a line v + ε(p × v) maps to Rv + ε(t × Rv + R(p × v)).
  const Mat3<T> r = glm::mat3_cast(q.real);
  const Vec3<T> t = translation(q);
  const Mat3<T> cross_t(Vec3<T>(0, t.z, -t.y), Vec3<T>(-t.z, 0, t.x), Vec3<T>(t.y, -t.x, 0));  // columns
  return {r, cross_t * r};
}

#define DQSKIN_INSTANTIATE(T)                                                       \
  template DualQuat<T> identity<T>();                                               \
  template DualQuat<T> quat_conjugate(const DualQuat<T>&);                          \
  template DualQuat<T> dual_conjugate(const DualQuat<T>&);                          \
  template DualQuat<T> full_conjugate(const DualQuat<T>&);                          \
  template Dual<T> norm(const DualQuat<T>&);                                        \
  template DualQuat<T> normalize(const DualQuat<T>&);                               \
  template DualQuat<T> inverse(const DualQuat<T>&);                                 \
  template bool is_unit(const DualQuat<T>&, T);                                     \
  template DualQuat<T> from_rotation_translation(const Quat<T>&, const Vec3<T>&);   \
  template Vec3<T> translation(const DualQuat<T>&);                                 \
  template DualQuat<T> from_rigid_matrix(const Mat4<T>&);                           \
  template Mat4<T> to_rigid_matrix(const DualQuat<T>&);                             \
  template Vec3<T> transform_point(const DualQuat<T>&, const Vec3<T>&);             \
  template Vec3<T> rotate_vector(const DualQuat<T>&, const Vec3<T>&);               \
  template DualMat3<T> line_transform(const DualQuat<T>&);
DQSKIN_INSTANTIATE(float)
DQSKIN_INSTANTIATE(double)
#undef DQSKIN_INSTANTIATE

}  // namespace dqskin
