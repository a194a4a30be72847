// dqskin dual-quaternion math core.
//
// Everything the skinning pipeline needs from dual quaternions, built on GLM's glm::tdualquat and
// quaternion functions. Every function is a template instantiated for float and double; the double
// instantiation is the precision the CPU reference (the oracle for the GPU paths) runs at.
//
// Papers, as cited in the implementation files:
//   [Kavan]      Kavan, Collins, Zara, O'Sullivan: Dual Quaternions for Rigid Transformation Blending /
//                Geometric Skinning with Approximate Dual Quaternion Blending.
//   [Kenwright]  Kenwright: Dual-Quaternion Interpolation.
//   [Pennestri]  Pennestri, Valentini: Dual Quaternions as a Tool for Rigid Body Motion Analysis.
//
// Conventions (docs/DESIGN.md §3.1): quaternions are GLM's (x, y, z, w) with w the scalar part. A unit dual
// quaternion for "rotate by r, then translate by t" is (r, 0.5 * (0, t) * r), which is GLM's
// tdualquat(r, t) constructor.
#pragma once

#ifndef GLM_ENABLE_EXPERIMENTAL
#define GLM_ENABLE_EXPERIMENTAL
#endif
#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtx/dual_quaternion.hpp>

#include <span>

namespace dqskin {

template <typename T> using Vec3 = glm::vec<3, T, glm::defaultp>;
template <typename T> using Mat3 = glm::mat<3, 3, T, glm::defaultp>;
template <typename T> using Mat4 = glm::mat<4, 4, T, glm::defaultp>;
template <typename T> using Quat = glm::qua<T, glm::defaultp>;
template <typename T> using DualQuat = glm::tdualquat<T, glm::defaultp>;

// A dual number a + εb with ε² = 0 [Kavan §3].
template <typename T>
struct Dual {
  T real{};
  T dual{};
};

// A dual vector a + εb: a dual quaternion whose scalar parts are zero. The logarithm of a unit dual
// quaternion is one, and so is a line in Plücker form (direction + ε moment).
template <typename T>
struct DualVec {
  Vec3<T> real{};
  Vec3<T> dual{};
};

// ---------------------------------------------------------------------------------------------------
// Algebra (product and sum are GLM's operators * and +).

// Identity: no rotation, no translation.
template <typename T> DualQuat<T> identity();

// The three conjugates [Kenwright appendix, footnote 1]:
//   quaternion conjugate  q* = r* + ε d*   : the inverse of a unit dual quaternion; transforms lines
//                                            (q (l + εm) q*) [Kavan §3].
//   dual conjugate        q̄  = r  − ε d
//   both                  q† = r* − ε d*   : the one that transforms points: q (1 + εv) q† = 1 + ε(R v + t)
//                                            [Kavan §3].
template <typename T> DualQuat<T> quat_conjugate(const DualQuat<T>& q);
template <typename T> DualQuat<T> dual_conjugate(const DualQuat<T>& q);
template <typename T> DualQuat<T> full_conjugate(const DualQuat<T>& q);

// Norm as a dual number: ||q|| = sqrt(q* q) = |r| + ε <r, d> / |r| [Kavan §3; Pennestri eq. 42].
// q is unit exactly when |r| = 1 and <r, d> = 0. Requires r != 0.
template <typename T> Dual<T> norm(const DualQuat<T>& q);

// Division by the dual-number norm: the projection onto unit dual quaternions that DLB uses [Kavan §4].
// Unlike glm::normalize (which divides by |r| only), the result also has <r, d> = 0. Requires r != 0.
template <typename T> DualQuat<T> normalize(const DualQuat<T>& q);

// q⁻¹ = q* / ||q||² [Kavan §3; Pennestri eq. 43], for any q with r != 0 (glm::inverse is right only for
// unit q).
template <typename T> DualQuat<T> inverse(const DualQuat<T>& q);

// True when |‖q‖ − 1| ≤ tolerance in both the real and the dual part of the norm.
template <typename T> bool is_unit(const DualQuat<T>& q, T tolerance);

// ---------------------------------------------------------------------------------------------------
// Conversions. Rigid matrices are column-major glm::mat4: columns 0-2 rotation, column 3 translation.

// Unit dual quaternion for "rotate by r (unit), then translate by t" [Kavan eq. 1; Kenwright eq. 1].
template <typename T> DualQuat<T> from_rotation_translation(const Quat<T>& r, const Vec3<T>& t);

// Translation of a unit dual quaternion: t = 2 d r* [Kavan §3; Kenwright eq. 2].
template <typename T> Vec3<T> translation(const DualQuat<T>& q);

// Unit dual quaternion of a rigid matrix. The 3×3 part must be a rotation (det +1); scale or shear must
// first be split off with split_joint_matrix. The sign is fixed: w ≥ 0.
template <typename T> DualQuat<T> from_rigid_matrix(const Mat4<T>& m);

// The rigid matrix of a unit dual quaternion.
template <typename T> Mat4<T> to_rigid_matrix(const DualQuat<T>& q);

// Image of point p: R p + t. q must be unit.
template <typename T> Vec3<T> transform_point(const DualQuat<T>& q, const Vec3<T>& p);

// Image of direction v (normals, tangents): R v; translation does not apply. q must be unit.
template <typename T> Vec3<T> rotate_vector(const DualQuat<T>& q, const Vec3<T>& v);

// The 3×3 dual matrix [Â] = R + ε [t]× R that maps line vectors v + ε(p × v) to their images
// [Pennestri eq. 20-21]. q must be unit.
template <typename T> struct DualMat3 {
  Mat3<T> real{};
  Mat3<T> dual{};
};
template <typename T> DualMat3<T> line_transform(const DualQuat<T>& q);

// ---------------------------------------------------------------------------------------------------
// Non-rigid joint matrices (docs/DESIGN.md §3.6).

// A joint matrix [A | t] split as A = R S: a rigid part [R | t] and a symmetric 3×3 S applied first,
// so that m p = R (S p) + t.
template <typename T>
struct JointSplit {
  DualQuat<T> rigid;  // unit; R has det +1
  Mat3<T> scale;      // symmetric; identity for rigid joints
  bool is_rigid;      // every entry of S − I within the tolerance
};

// Polar decomposition A = R S with R the rotation nearest to A (the maximiser of tr(Rᵀ A)), which for
// det A > 0 is the polar factor and S is symmetric positive definite. Mirrored joints (det A < 0) keep
// R a rotation and give S a negative eigenvalue; singular A (a zero scale) gives a singular S. Never
// produces NaN for finite input. The default tolerance is docs/DESIGN.md §3.6's 1e-5.
template <typename T> JointSplit<T> split_joint_matrix(const Mat4<T>& m, T tolerance = T(1e-5));

// The rotation nearest to M in the Frobenius norm (maximising tr(Rᵀ M)), as a unit quaternion with
// w ≥ 0, by Horn's quaternion method: the eigenvector of the largest eigenvalue of a symmetric 4×4.
template <typename T> Quat<T> nearest_rotation(const Mat3<T>& m);

// ---------------------------------------------------------------------------------------------------
// Screw parameters [Kenwright eq. 8-11; Kavan eq. 2; Pennestri eq. 7, 14].
//
// q = cos(θ̂/2) + (l + εm) sin(θ̂/2) with dual angle θ̂ = θ + εd: rotation by θ about the axis with unit
// direction l and moment m = p × l (p any point of the axis), and translation d along l.
template <typename T>
struct Screw {
  T theta{};          // rotation angle in [0, 2π]; the sign of q picks θ or 2π − θ with −l
  T d{};              // translation along the axis (the pitch translation)
  Vec3<T> axis{};     // unit direction l
  Vec3<T> moment{};   // m = p × l
};

// Screw of a unit dual quaternion. Stable at every angle: a pure translation (θ = 0 or 2π exactly) gets
// the translation direction as its axis through the origin (m = 0), the identity gets axis +z. Near
// θ = 0 or 2π with a translation across the axis, the axis really is far away, so |m| grows like
// 1/sin(θ/2) but stays finite.
template <typename T> Screw<T> to_screw(const DualQuat<T>& q);

// Unit dual quaternion of a screw [Kenwright eq. 10]. axis must be unit, moment ⟂ axis.
template <typename T> DualQuat<T> from_screw(const Screw<T>& s);

// The point of the screw axis nearest to the origin: l × m.
template <typename T> Vec3<T> point_on_axis(const Screw<T>& s);

// ---------------------------------------------------------------------------------------------------
// Exponential, logarithm and power of unit dual quaternions [Kavan §3; Pennestri eq. 44-48].

// log q = (l + εm) θ̂/2, for unit q. Smooth through θ = 0 (where it is ε t/2).
template <typename T> DualVec<T> log(const DualQuat<T>& q);

// exp(x) for a dual vector x; the inverse of log for |x.real| < π.
template <typename T> DualQuat<T> exp(const DualVec<T>& x);

// q^t = exp(t log q) = cos(t θ̂/2) + (l + εm) sin(t θ̂/2), for unit q and any real t.
template <typename T> DualQuat<T> pow(const DualQuat<T>& q, T t);

// ---------------------------------------------------------------------------------------------------
// Interpolation of two poses, t in [0, 1] (values outside extrapolate). Inputs are unit. Each takes the
// shorter way: q is first flipped to p's hemisphere (Kavan §3 antipodality; −q is the same pose).

// ScLERP(t; p, q) = p (p* q)^t [Kavan §4; Pennestri eq. 30; Kenwright eq. 14].
template <typename T> DualQuat<T> sclerp(const DualQuat<T>& p, const DualQuat<T>& q, T t);

// DLB(t; p, q) = ((1−t) p + t q) / ||(1−t) p + t q|| [Kavan §4; Pennestri Alg. 1 (sDLB)].
template <typename T> DualQuat<T> dlb(const DualQuat<T>& p, const DualQuat<T>& q, T t);

// SEP(LERP): rotation by SLERP and translation by LERP, separately [Kenwright eq. 3].
template <typename T> DualQuat<T> sep_lerp(const DualQuat<T>& p, const DualQuat<T>& q, T t);

// KenLERP [Kenwright eq. 6]: bias β moves from SEP(LERP) (β = 0, decoupled) to ScLERP (β = 1, coupled);
// β > 1 amplifies the coupling (extrapolates past ScLERP).
template <typename T> DualQuat<T> ken_lerp(const DualQuat<T>& p, const DualQuat<T>& q, T t, T beta);

// ---------------------------------------------------------------------------------------------------
// Blending of n poses with weights. All spans have the same, non-zero size. Weights need not be convex
// (Pennestri §6 uses Lagrange weights), but skinning passes convex ones.

// DLB(w; q1..qn) = Σ wᵢ qᵢ / ||Σ wᵢ qᵢ|| [Kavan §4; Pennestri eq. 33]. Antipodality (docs/DESIGN.md §3.5): each qᵢ
// is first flipped to the hemisphere of the one with the largest weight. With non-negative weights the
// sum's real part cannot vanish.
template <typename T> DualQuat<T> blend_dlb(std::span<const DualQuat<T>> q, std::span<const T> w);

struct DibOptions {
  double precision = 1e-12;  // stop when max(|x.real|, |x.dual|) of the correction is below this;
                             // a value under 16 ulps of the blend type is raised to that
  int max_iterations = 32;   // stop after this many corrections
};

template <typename T>
struct DibResult {
  DualQuat<T> blend;
  int iterations;  // corrections b ← b exp(x) applied; 0 when DLB was already exact
  bool converged;  // false when max_iterations ran out first
};

// DIB [Kavan §4 (algorithm box); Pennestri Alg. 3]: start at DLB, then b ← b exp(Σ wᵢ log(b* qᵢ)) until
// the correction is below the precision. Each b* qᵢ is taken in its shorter form (w ≥ 0) before its
// log, so the result does not depend on the inputs' signs. The weights are divided by their sum.
template <typename T>
DibResult<T> blend_dib(std::span<const DualQuat<T>> q, std::span<const T> w, const DibOptions& options = {});

// QLB: Σ wᵢ qᵢ / |Σ wᵢ qᵢ| for rotations, with the same antipodality rule [Kavan §4]. (SLERP of two
// rotations is glm::slerp.)
template <typename T> Quat<T> blend_qlb(std::span<const Quat<T>> q, std::span<const T> w);

// LBS: Σ wᵢ Mᵢ, the linear blend of matrices that skinning used before dual quaternions [Kavan §6].
template <typename T> Mat4<T> blend_lbs(std::span<const Mat4<T>> m, std::span<const T> w);

// ---------------------------------------------------------------------------------------------------
// Rigid motion from point correspondences [Pennestri §4].

template <typename T>
struct RigidFit {
  bool valid = false;  // false for fewer than 3 pairs, different counts, or collinear / coincident points
  DualQuat<T> motion;  // unit; maps every from[i] as close as possible to to[i]
  Screw<T> screw;      // screw parameters of motion
  T rms_residual{};    // sqrt(mean |motion(from[i]) − to[i]|²); 0 for exactly rigid data
};

// Least-squares rigid motion: centroids as in [Pennestri eq. 22], the rotation maximising Σ (R rᵢ)·sᵢ
// over the centred points (Horn's closed form; exact least squares, where the dual QR of Pennestri
// eq. 27-29 is only exact for error-free data), then t = c − R c₀.
template <typename T>
RigidFit<T> fit_rigid_motion(std::span<const Vec3<T>> from, std::span<const Vec3<T>> to);

}  // namespace dqskin
