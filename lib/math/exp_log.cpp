// Exponential, logarithm and power of unit dual quaternions [Kavan §3; Pennestri appendix eq. 44-48].
#include "dqskin/dual_quat.hpp"

#include <cmath>
#include <limits>

namespace dqskin {
namespace {

// sin(φ)/φ and (cos φ − sin(φ)/φ)/φ², by their Taylor series where the closed forms cancel.
template <typename T>
void sinc_terms(T phi, T& sinc, T& curl) {
  if (phi < T(1e-2)) {
    const T p2 = phi * phi;
    sinc = T(1) - p2 / T(6) + p2 * p2 / T(120);
    curl = T(-1) / T(3) + p2 / T(30) - p2 * p2 / T(840);
  } else {
    sinc = std::sin(phi) / phi;
    curl = (std::cos(phi) - sinc) / (phi * phi);
  }
}

}  // namespace

template <typename T>
DualVec<T> log(const DualQuat<T>& q) {
  // log q = (l + εm)(θ + εd)/2 = φ l + ε ½ (d l + θ m) with φ = θ/2 [Kavan §3; Pennestri eq. 47].
  // Substituting m from to_screw: ε ½ (d l + φ (t × l) + φ cot φ t⊥), smooth as φ → 0 (φ cot φ → 1).
  const Vec3<T> v(q.real.x, q.real.y, q.real.z);
  const T s = glm::length(v), w = q.real.w;
  const T phi = std::atan2(s, w);
  const Vec3<T> t = translation(q);
  const T eps = std::numeric_limits<T>::epsilon();
  if (s <= eps * eps) {  // no rotation axis: a pure translation (φ = 0), or its negation (φ = π)
    const T length = glm::length(t);
    const Vec3<T> axis = length > T(0) ? t / length : Vec3<T>(0, 0, 1);
    return {phi * axis, T(0.5) * t};
  }
  const Vec3<T> l = v / s;
  const T d = glm::dot(t, l);
  const Vec3<T> t_perp = t - d * l;
  return {phi * l, T(0.5) * (d * l + phi * glm::cross(t, l) + (phi * w / s) * t_perp)};
}

template <typename T>
DualQuat<T> exp(const DualVec<T>& x) {
  // x = (l + εm)(φ + εδ) with δ = b·l. exp x = cos φ̂ + (l + εm) sin φ̂ [Kavan §3; Pennestri eq. 45]:
  //   real = (cos φ, a sinc φ)
  //   dual = (−(a·b) sinc φ, b sinc φ + (a·b) a (cos φ − sinc φ)/φ²)
  const Vec3<T>& a = x.real;
  const Vec3<T>& b = x.dual;
  const T phi = glm::length(a);
  T sinc, curl;
  sinc_terms(phi, sinc, curl);
  const T ab = glm::dot(a, b);
  return {Quat<T>(std::cos(phi), sinc * a), Quat<T>(-ab * sinc, sinc * b + (ab * curl) * a)};
}

template <typename T>
DualQuat<T> pow(const DualQuat<T>& q, T t) {
  const DualVec<T> l = log(q);
  return exp(DualVec<T>{t * l.real, t * l.dual});  // [Pennestri eq. 48]
}

template DualVec<float> log(const DualQuat<float>&);
template DualVec<double> log(const DualQuat<double>&);
template DualQuat<float> exp(const DualVec<float>&);
template DualQuat<double> exp(const DualVec<double>&);
template DualQuat<float> pow(const DualQuat<float>&, float);
template DualQuat<double> pow(const DualQuat<double>&, double);

}  // namespace dqskin
