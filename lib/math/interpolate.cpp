// Interpolation of two rigid poses: ScLERP and DLB [Kavan §4; Pennestri §5.1-5.2], SEP(LERP) and KenLERP
// [Kenwright §3].
#include "dqskin/dual_quat.hpp"
#include "hemisphere.hpp"

namespace dqskin {

template <typename T>
DualQuat<T> sclerp(const DualQuat<T>& p, const DualQuat<T>& q, T t) {
  // ScLERP(t; p, q) = p (p* q)^t  [Kavan §4; Pennestri eq. 30]. Kenwright's eq. 5 prints ζ*_B for ζ*_A.
  return p * pow(quat_conjugate(p) * detail::in_hemisphere_of(p.real, q), t);
}

template <typename T>
DualQuat<T> dlb(const DualQuat<T>& p, const DualQuat<T>& q, T t) {
  return normalize(p * (T(1) - t) + detail::in_hemisphere_of(p.real, q) * t);  // [Pennestri Alg. 1]
}

template <typename T>
DualQuat<T> sep_lerp(const DualQuat<T>& p, const DualQuat<T>& q, T t) {
  // [Kenwright eq. 3]: SLERP the rotations (glm::slerp takes the short way), LERP the translations.
  return from_rotation_translation(glm::slerp(p.real, q.real, t), glm::mix(translation(p), translation(q), t));
}

template <typename T>
DualQuat<T> ken_lerp(const DualQuat<T>& p, const DualQuat<T>& q, T t, T beta) {
  // [Kenwright eq. 6]. The text fixes the direction (β = 0 decoupled, β = 1 ScLERP), which eq. 6's
  // LERP(v0, v1, β) with v0 from ScLERP has backwards; we follow the text. The rotation of ScLERP is the
  // SLERP of the rotations, so both ends share it and only the translation moves with β.
  const DualQuat<T> coupled = sclerp(p, q, t);
  const DualQuat<T> decoupled = sep_lerp(p, q, t);
  return from_rotation_translation(glm::slerp(decoupled.real, coupled.real, beta),
                                   glm::mix(translation(decoupled), translation(coupled), beta));
}

#define DQSKIN_INSTANTIATE(T)                                                          \
  template DualQuat<T> sclerp(const DualQuat<T>&, const DualQuat<T>&, T);              \
  template DualQuat<T> dlb(const DualQuat<T>&, const DualQuat<T>&, T);                 \
  template DualQuat<T> sep_lerp(const DualQuat<T>&, const DualQuat<T>&, T);            \
  template DualQuat<T> ken_lerp(const DualQuat<T>&, const DualQuat<T>&, T, T);
DQSKIN_INSTANTIATE(float)
DQSKIN_INSTANTIATE(double)
#undef DQSKIN_INSTANTIATE

}  // namespace dqskin
