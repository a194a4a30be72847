#include "dqskin/dual_quat.hpp"
#include "test_support.hpp"

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>

namespace dqskin {
namespace {

using test::Random;

Mat4<double> compose(const DualQuat<double>& rigid, const Mat3<double>& s) {
  Mat4<double> m = to_rigid_matrix(rigid);
  const Mat3<double> a = Mat3<double>(m) * s;
  for (int c = 0; c < 3; ++c) m[c] = glm::dvec4(a[c], 0);
  return m;
}

void expect_reconstructs(const Mat4<double>& m, const JointSplit<double>& split, double tol) {
  const Mat3<double> r = glm::mat3_cast(split.rigid.real);
  const Mat3<double> a = r * split.scale;
  for (int c = 0; c < 3; ++c)
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(a[c][k], m[c][k], tol) << "A(" << k << "," << c << ")";
  EXPECT_LE(glm::distance(translation(split.rigid), Vec3<double>(m[3])), tol);
  EXPECT_NEAR(glm::determinant(r), 1.0, 1e-12);
  for (int c = 0; c < 3; ++c)
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(split.scale[c][k], split.scale[k][c], 1e-12) << "S symmetric";
}

TEST(NearestRotation, ReturnsTheRotationOfARotationMatrix) {
  Random rng(20);
  for (int i = 0; i < 1000; ++i) {
    const Quat<double> r = rng.rotation();
    const Quat<double> back = nearest_rotation(glm::mat3_cast(r));
    EXPECT_NEAR(std::abs(glm::dot(back, r)), 1.0, 1e-12);
    EXPECT_GE(back.w, 0.0);
  }
}

TEST(JointSplit, RigidMatrixIsRigidWithIdentityScale) {
  Random rng(21);
  for (int i = 0; i < 200; ++i) {
    const DualQuat<double> q = rng.pose();
    const Mat4<double> m = to_rigid_matrix(q);
    const JointSplit<double> split = split_joint_matrix(m);
    EXPECT_TRUE(split.is_rigid);
    EXPECT_EQ(split.scale, Mat3<double>(1));
    EXPECT_SAME_POSE(split.rigid, q, 1e-12);
  }
}

TEST(JointSplit, ScaleWithinToleranceCountsAsRigid) {
  // docs/DESIGN.md §3.6: non-rigid means scale or shear beyond 1e-5.
  const Mat4<double> almost = glm::scale(Mat4<double>(1), Vec3<double>(1 + 5e-6, 1, 1 - 5e-6));
  EXPECT_TRUE(split_joint_matrix(almost).is_rigid);
  const Mat4<double> beyond = glm::scale(Mat4<double>(1), Vec3<double>(1 + 2e-5, 1, 1));
  EXPECT_FALSE(split_joint_matrix(beyond).is_rigid);
}

TEST(JointSplit, RecoversRotationAndSymmetricScale) {
  Random rng(22);
  for (int i = 0; i < 500; ++i) {
    const DualQuat<double> rigid = rng.pose();
    // Random symmetric positive definite S = Q diag(s) Qᵀ: non-uniform scale along rotated axes (shear).
    const Mat3<double> q = glm::mat3_cast(rng.rotation());
    const Mat3<double> d(Vec3<double>(rng.uniform(0.1, 3), 0, 0), Vec3<double>(0, rng.uniform(0.1, 3), 0),
                         Vec3<double>(0, 0, rng.uniform(0.1, 3)));
    const Mat3<double> s = q * d * glm::transpose(q);
    const Mat4<double> m = compose(rigid, s);
    const JointSplit<double> split = split_joint_matrix(m);
    EXPECT_FALSE(split.is_rigid);
    EXPECT_SAME_POSE(split.rigid, rigid, 1e-10);
    expect_reconstructs(m, split, 1e-10);
    for (int c = 0; c < 3; ++c)
      for (int k = 0; k < 3; ++k) EXPECT_NEAR(split.scale[c][k], s[c][k], 1e-10);
  }
}

TEST(JointSplit, UniformScaleGoesToScaleNotRotation) {
  const DualQuat<double> rigid =
      from_rotation_translation(glm::angleAxis(0.7, glm::normalize(Vec3<double>(1, 2, 3))), Vec3<double>(4, 5, 6));
  const Mat4<double> m = compose(rigid, Mat3<double>(0.3));
  const JointSplit<double> split = split_joint_matrix(m);
  EXPECT_FALSE(split.is_rigid);
  EXPECT_SAME_POSE(split.rigid, rigid, 1e-12);
  for (int c = 0; c < 3; ++c)
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(split.scale[c][k], c == k ? 0.3 : 0.0, 1e-12);
}

TEST(JointSplit, MirroredJointKeepsAProperRotation) {
  // det A < 0 (a negative scale): R stays a rotation and S takes the reflection, still A = R S.
  Random rng(23);
  for (int i = 0; i < 200; ++i) {
    const Mat4<double> m = compose(rng.pose(), Mat3<double>(Vec3<double>(-1, 0, 0), Vec3<double>(0, 2, 0),
                                                            Vec3<double>(0, 0, 0.5)));
    const JointSplit<double> split = split_joint_matrix(m);
    EXPECT_FALSE(split.is_rigid);
    expect_reconstructs(m, split, 1e-10);
    EXPECT_LT(glm::determinant(split.scale), 0.0);
  }
}

TEST(JointSplit, SingularMatrixGivesFiniteSplit) {
  // glTF allows a zero scale (hiding a part); the split must not produce NaN.
  Random rng(24);
  for (const Vec3<double> scale : {Vec3<double>(0, 1, 1), Vec3<double>(0, 0, 2), Vec3<double>(0)}) {
    const Mat4<double> m = compose(rng.pose(), Mat3<double>(Vec3<double>(scale.x, 0, 0),
                                                            Vec3<double>(0, scale.y, 0), Vec3<double>(0, 0, scale.z)));
    const JointSplit<double> split = split_joint_matrix(m);
    EXPECT_FALSE(split.is_rigid);
    for (int k = 0; k < 4; ++k) EXPECT_TRUE(std::isfinite(split.rigid.real[k]) && std::isfinite(split.rigid.dual[k]));
    expect_reconstructs(m, split, 1e-10);
  }
}

TEST(JointSplit, FloatSplitMatchesDouble) {
  Random rng(25);
  for (int i = 0; i < 200; ++i) {
    const Mat4<double> m = compose(rng.pose(1), Mat3<double>(Vec3<double>(1.5, 0.2, 0), Vec3<double>(0.2, 0.8, 0),
                                                             Vec3<double>(0, 0, 1.1)));
    const JointSplit<double> d = split_joint_matrix(m);
    const JointSplit<float> f = split_joint_matrix(Mat4<float>(m));
    EXPECT_SAME_POSE(DualQuat<double>(f.rigid), d.rigid, 1e-6);
    for (int c = 0; c < 3; ++c)
      for (int k = 0; k < 3; ++k) EXPECT_NEAR(double(f.scale[c][k]), d.scale[c][k], 1e-6);
  }
}

}  // namespace
}  // namespace dqskin
