#include "dqskin/dual_quat.hpp"
#include "test_support.hpp"

#include <cmath>
#include <limits>

namespace dqskin {
namespace {

using test::Random;

constexpr double kDoubleTol = 1e-12;
constexpr float kFloatTol = 1e-6f;

TEST(DualQuatAlgebra, ProductComposesTransformsLikeMatrices) {
  Random rng(1);
  for (int i = 0; i < 1000; ++i) {
    const DualQuat<double> a = rng.pose(), b = rng.pose();
    const Mat4<double> expected = to_rigid_matrix(a) * to_rigid_matrix(b);
    const Mat4<double> actual = to_rigid_matrix(a * b);
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r) ASSERT_NEAR(actual[c][r], expected[c][r], 1e-11);
  }
}

TEST(DualQuatAlgebra, FullConjugateTransformsPointsAsSandwich) {
  // q (1 + εv) q† = 1 + ε(R v + t): the conjugate of both kinds is the one that transforms points.
  Random rng(2);
  for (int i = 0; i < 1000; ++i) {
    const DualQuat<double> q = rng.pose();
    const Vec3<double> v = rng.vec3(5);
    const DualQuat<double> point(Quat<double>(1, 0, 0, 0), Quat<double>(0, v.x, v.y, v.z));
    const DualQuat<double> image = q * point * full_conjugate(q);
    const Vec3<double> expected = transform_point(q, v);
    EXPECT_NEAR(image.real.w, 1, kDoubleTol);
    EXPECT_NEAR(glm::length(Vec3<double>(image.real.x, image.real.y, image.real.z)), 0, kDoubleTol);
    EXPECT_NEAR(image.dual.w, 0, kDoubleTol);
    EXPECT_NEAR(glm::distance(Vec3<double>(image.dual.x, image.dual.y, image.dual.z), expected), 0, 1e-11);
  }
}

TEST(DualQuatAlgebra, QuaternionConjugateInvertsUnitDualQuaternions) {
  Random rng(3);
  for (int i = 0; i < 1000; ++i) {
    const DualQuat<double> q = rng.pose();
    EXPECT_DUALQUAT_NEAR(q * quat_conjugate(q), identity<double>(), kDoubleTol);
    EXPECT_DUALQUAT_NEAR(quat_conjugate(q) * q, identity<double>(), kDoubleTol);
  }
}

TEST(DualQuatAlgebra, DualConjugateNegatesOnlyTheDualPart) {
  const DualQuat<double> q(Quat<double>(1, 2, 3, 4), Quat<double>(5, 6, 7, 8));
  const DualQuat<double> c = dual_conjugate(q);
  EXPECT_EQ(c.real, q.real);
  EXPECT_EQ(c.dual, -q.dual);
}

TEST(DualQuatAlgebra, NormIsADualNumber) {
  // ||q|| = |r| + ε <r, d>/|r| [Kavan §3]; it is multiplicative.
  const DualQuat<double> q(Quat<double>(1, 2, 3, 4), Quat<double>(5, 6, 7, 8));
  const Dual<double> n = norm(q);
  EXPECT_NEAR(n.real, std::sqrt(30.0), kDoubleTol);
  EXPECT_NEAR(n.dual, (5 + 12 + 21 + 32) / std::sqrt(30.0), kDoubleTol);

  const DualQuat<double> p(Quat<double>(0.5, -1, 2, 0.25), Quat<double>(-3, 1, 0.5, 2));
  const Dual<double> np = norm(p), npq = norm(p * q);
  EXPECT_NEAR(npq.real, np.real * n.real, 1e-11);
  EXPECT_NEAR(npq.dual, np.real * n.dual + np.dual * n.real, 1e-11);  // dual-number product
}

TEST(DualQuatAlgebra, UnitPosesHaveUnitNorm) {
  Random rng(4);
  for (int i = 0; i < 100; ++i) EXPECT_TRUE(is_unit(rng.pose(), 1e-12));
  EXPECT_FALSE(is_unit(DualQuat<double>(Quat<double>(1, 0, 0, 0), Quat<double>(0.1, 0, 0, 0)), 1e-3));
  EXPECT_FALSE(is_unit(DualQuat<double>(Quat<double>(2, 0, 0, 0), Quat<double>(0, 0, 0, 0)), 1e-3));
}

TEST(DualQuatAlgebra, NormalizeProjectsOntoUnitDualQuaternions) {
  // glm::normalize divides by |r| only and leaves <r, d> ≠ 0; ours must give a unit dual quaternion
  // and keep the pose of an already unit one.
  const DualQuat<double> q(Quat<double>(1, 2, 3, 4), Quat<double>(5, 6, 7, 8));
  const DualQuat<double> n = normalize(q);
  EXPECT_TRUE(is_unit(n, 1e-14));
  EXPECT_FALSE(is_unit(glm::normalize(q), 1e-3));

  Random rng(5);
  for (int i = 0; i < 100; ++i) {
    const DualQuat<double> p = rng.pose();
    EXPECT_DUALQUAT_NEAR(normalize(p * 3.5), p, kDoubleTol);
    EXPECT_DUALQUAT_NEAR(normalize(normalize(p * 0.25)), normalize(p * 0.25), kDoubleTol);
  }
}

TEST(DualQuatAlgebra, InverseWorksForNonUnitDualQuaternions) {
  const DualQuat<double> q(Quat<double>(1, 2, 3, 4), Quat<double>(5, 6, 7, 8));
  EXPECT_DUALQUAT_NEAR(q * inverse(q), identity<double>(), kDoubleTol);
  EXPECT_DUALQUAT_NEAR(inverse(q) * q, identity<double>(), kDoubleTol);
  Random rng(6);
  for (int i = 0; i < 100; ++i) {
    const DualQuat<double> p = rng.pose();
    EXPECT_DUALQUAT_NEAR(inverse(p), quat_conjugate(p), kDoubleTol);
  }
}

TEST(DualQuatConversion, RotationTranslationRoundTrip) {
  Random rng(7);
  for (int i = 0; i < 1000; ++i) {
    const Quat<double> r = rng.rotation();
    const Vec3<double> t = rng.vec3(100);
    const DualQuat<double> q = from_rotation_translation(r, t);
    EXPECT_LE(glm::distance(translation(q), t), 1e-12 * 100);
    EXPECT_EQ(q.real, r);
    // docs/DESIGN.md §3.1: dual = 0.5 * quat(0, t) * r
    EXPECT_DUALQUAT_NEAR(q, DualQuat<double>(r, Quat<double>(0, t.x, t.y, t.z) * r * 0.5), kDoubleTol * 100);
  }
}

template <typename T>
void expect_matrix_round_trip(unsigned seed, T tolerance) {
  Random rng(seed);
  for (int i = 0; i < 1000; ++i) {
    const Mat4<T> m = Mat4<T>(to_rigid_matrix(rng.pose(1)));
    const Mat4<T> back = to_rigid_matrix(from_rigid_matrix(m));
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r) ASSERT_NEAR(back[c][r], m[c][r], tolerance) << "entry " << c << "," << r;
  }
}

TEST(DualQuatConversion, MatrixRoundTripIsExactToDoubleRounding) { expect_matrix_round_trip<double>(8, kDoubleTol); }
TEST(DualQuatConversion, MatrixRoundTripIsExactToFloatRounding) { expect_matrix_round_trip<float>(9, kFloatTol); }

TEST(DualQuatConversion, DualQuaternionMatrixRoundTripKeepsThePose) {
  Random rng(10);
  for (int i = 0; i < 1000; ++i) {
    const DualQuat<double> q = rng.pose(1);
    EXPECT_SAME_POSE(from_rigid_matrix(to_rigid_matrix(q)), q, kDoubleTol);
    const DualQuat<float> f(q);
    EXPECT_SAME_POSE(from_rigid_matrix(to_rigid_matrix(f)), f, kFloatTol);
  }
}

TEST(DualQuatConversion, FromRigidMatrixHasNonNegativeScalarPart) {
  // 270° about z: GLM's quat_cast may return either sign; ours fixes w ≥ 0 so equal inputs give equal bits.
  const Mat4<double> m = to_rigid_matrix(from_rotation_translation(
      glm::angleAxis(1.5 * M_PI, Vec3<double>(0, 0, 1)), Vec3<double>(1, 2, 3)));
  EXPECT_GE(from_rigid_matrix(m).real.w, 0.0);
}

TEST(DualQuatConversion, TransformPointMatchesMatrixAndRotateVectorIgnoresTranslation) {
  Random rng(11);
  for (int i = 0; i < 1000; ++i) {
    const DualQuat<double> q = rng.pose();
    const Mat4<double> m = to_rigid_matrix(q);
    const Vec3<double> p = rng.vec3(3);
    EXPECT_LE(glm::distance(transform_point(q, p), Vec3<double>(m * glm::dvec4(p, 1))), 1e-12 * 20);
    EXPECT_LE(glm::distance(rotate_vector(q, p), Vec3<double>(m * glm::dvec4(p, 0))), 1e-12 * 20);
  }
}

TEST(DualQuatConversion, LineTransformMatchesPennestriFourPointExample) {
  // [Pennestri §4]: the motion of §2's example has [Â] = [[−ε, −1, 2ε], [1, −ε, −2ε], [2ε, 2ε, 1]].
  const DualQuat<double> q =
      from_rotation_translation(glm::angleAxis(M_PI / 2, Vec3<double>(0, 0, 1)), Vec3<double>(2, 2, 1));
  const DualMat3<double> a = line_transform(q);
  const double real[3][3] = {{0, -1, 0}, {1, 0, 0}, {0, 0, 1}};  // [row][column]
  const double dual[3][3] = {{-1, 0, 2}, {0, -1, -2}, {2, 2, 0}};
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(a.real[c][r], real[r][c], kDoubleTol) << r << "," << c;
      EXPECT_NEAR(a.dual[c][r], dual[r][c], kDoubleTol) << r << "," << c;
    }
  }
}

TEST(DualQuatConversion, LineTransformMapsLinesThroughTransformedPoints) {
  // A line through p with direction v is v + ε(p × v); its image must pass through q(p) along R v.
  Random rng(12);
  for (int i = 0; i < 200; ++i) {
    const DualQuat<double> q = rng.pose();
    const Vec3<double> p = rng.vec3(3), v = glm::normalize(rng.vec3(1));
    const DualMat3<double> a = line_transform(q);
    const Vec3<double> dir = a.real * v;
    const Vec3<double> moment = a.real * glm::cross(p, v) + a.dual * v;
    EXPECT_LE(glm::distance(dir, rotate_vector(q, v)), 1e-12);
    EXPECT_LE(glm::distance(moment, glm::cross(transform_point(q, p), dir)), 1e-11);
  }
}

}  // namespace
}  // namespace dqskin

namespace dqskin {
namespace {

TEST(TestSupport, NanNeverPassesAComparison) {
  const double n = std::numeric_limits<double>::quiet_NaN();
  const DualQuat<double> a(Quat<double>(n, n, n, n), Quat<double>(n, n, n, n));
  EXPECT_EQ(test::max_abs_diff(a, identity<double>()), std::numeric_limits<double>::infinity());
  EXPECT_EQ(test::pose_diff(a, identity<double>()), std::numeric_limits<double>::infinity());
}

}  // namespace
}  // namespace dqskin
