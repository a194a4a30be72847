// Least-squares rigid motion from point correspondences and its screw [Pennestri §4].
#include "dqskin/dual_quat.hpp"

#include <cmath>
#include <limits>

namespace dqskin {
namespace {

template <typename T>
Vec3<T> centroid(std::span<const Vec3<T>> p) {  // [Pennestri eq. 22]
  Vec3<T> sum(0);
  for (const Vec3<T>& x : p) sum += x;
  return sum / T(p.size());
}

// True when the centred points span at least a plane, so that the rotation is determined.
template <typename T>
bool spans_a_plane(std::span<const Vec3<T>> p, const Vec3<T>& c) {
  size_t far = 0;
  T extent2 = 0;
  for (size_t i = 0; i < p.size(); ++i) {
    const T d2 = glm::dot(p[i] - c, p[i] - c);
    if (d2 > extent2) extent2 = d2, far = i;
  }
  if (!(extent2 > T(0))) return false;
  const T tolerance = T(1e3) * std::numeric_limits<T>::epsilon() * extent2;
  for (const Vec3<T>& x : p)
    if (glm::length(glm::cross(p[far] - c, x - c)) > tolerance) return true;
  return false;
}

}  // namespace

template <typename T>
RigidFit<T> fit_rigid_motion(std::span<const Vec3<T>> from, std::span<const Vec3<T>> to) {
  RigidFit<T> fit;
  if (from.size() < 3 || from.size() != to.size()) return fit;
  const Vec3<T> c0 = centroid(from), c1 = centroid(to);
  if (!spans_a_plane(from, c0)) return fit;

  // Maximise Σ (sᵢ − c1)·R(rᵢ − c0) = tr(Rᵀ M) with M = Σ (sᵢ − c1)(rᵢ − c0)ᵀ.
  Mat3<T> m(T(0));
  for (size_t i = 0; i < from.size(); ++i) m += glm::outerProduct(to[i] - c1, from[i] - c0);
  const Quat<T> r = nearest_rotation(m);

  fit.valid = true;
  fit.motion = from_rotation_translation(r, c1 - r * c0);
  fit.screw = to_screw(fit.motion);
  T sum2 = 0;
  for (size_t i = 0; i < from.size(); ++i) {
    const Vec3<T> e = transform_point(fit.motion, from[i]) - to[i];
    sum2 += glm::dot(e, e);
  }
  fit.rms_residual = std::sqrt(sum2 / T(from.size()));
  return fit;
}

template RigidFit<float> fit_rigid_motion(std::span<const Vec3<float>>, std::span<const Vec3<float>>);
template RigidFit<double> fit_rigid_motion(std::span<const Vec3<double>>, std::span<const Vec3<double>>);

}  // namespace dqskin
