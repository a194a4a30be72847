#include "dqskin/dual_quat.hpp"
#include "test_support.hpp"

#include <cmath>
#include <vector>

namespace dqskin {
namespace {

using test::Random;

TEST(RigidFit, PennestriFourPointExampleRecoversTheScrew) {
  // [Pennestri §4, numerical example]: four points before and after the motion of §2's example.
  const std::vector<Vec3<double>> from = {{1, 0, 0}, {1, 2, 0}, {1, 2, 1}, {0, 2, 1}};
  const std::vector<Vec3<double>> to = {{2, 3, 1}, {0, 3, 1}, {0, 3, 2}, {0, 2, 2}};
  const RigidFit<double> fit = fit_rigid_motion<double>(from, to);
  ASSERT_TRUE(fit.valid);
  EXPECT_NEAR(fit.rms_residual, 0.0, 1e-12);
  // "The screw motion parameters coincide with those obtained in the previous numerical example."
  EXPECT_NEAR(fit.screw.theta, M_PI / 2, 1e-12);
  EXPECT_NEAR(fit.screw.d, 1.0, 1e-12);
  EXPECT_LE(glm::distance(fit.screw.axis, Vec3<double>(0, 0, 1)), 1e-12);
  EXPECT_LE(glm::distance(point_on_axis(fit.screw), Vec3<double>(0, 2, 0)), 1e-12);
  // and the dual transform matrix of the paper.
  const DualMat3<double> a = line_transform(fit.motion);
  const double dual[3][3] = {{-1, 0, 2}, {0, -1, -2}, {2, 2, 0}};
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(a.dual[c][r], dual[r][c], 1e-12);
}

TEST(RigidFit, RecoversExactMotionsFromThreeOrMorePoints) {
  Random rng(60);
  for (int i = 0; i < 500; ++i) {
    const DualQuat<double> motion = rng.pose();
    std::vector<Vec3<double>> from, to;
    const size_t n = 3 + size_t(i % 6);
    for (size_t k = 0; k < n; ++k) {
      from.push_back(rng.vec3(2));
      to.push_back(transform_point(motion, from.back()));
    }
    const RigidFit<double> fit = fit_rigid_motion<double>(from, to);
    ASSERT_TRUE(fit.valid);
    EXPECT_SAME_POSE(fit.motion, motion, 1e-10);
    EXPECT_LE(fit.rms_residual, 1e-12);
  }
}

TEST(RigidFit, IsTheLeastSquaresFitForNoisyPoints) {
  // With measurement noise, no rigid motion near the fit does better than the fit itself.
  Random rng(61);
  for (int i = 0; i < 100; ++i) {
    const DualQuat<double> motion = rng.pose();
    std::vector<Vec3<double>> from, to;
    for (int k = 0; k < 12; ++k) {
      from.push_back(rng.vec3(2));
      to.push_back(transform_point(motion, from.back()) + rng.vec3(0.05));
    }
    const RigidFit<double> fit = fit_rigid_motion<double>(from, to);
    ASSERT_TRUE(fit.valid);
    EXPECT_GT(fit.rms_residual, 0.0);
    auto rms = [&](const DualQuat<double>& q) {
      double sum = 0;
      for (size_t k = 0; k < from.size(); ++k) sum += glm::dot(transform_point(q, from[k]) - to[k], transform_point(q, from[k]) - to[k]);
      return std::sqrt(sum / double(from.size()));
    };
    EXPECT_NEAR(rms(fit.motion), fit.rms_residual, 1e-12);
    EXPECT_LE(fit.rms_residual, rms(motion));
    for (int k = 0; k < 20; ++k) {
      const DualQuat<double> nudge = from_rotation_translation(
          glm::angleAxis(rng.uniform(1e-4, 1e-2), glm::normalize(rng.vec3(1))), rng.vec3(1e-3));
      EXPECT_LE(fit.rms_residual, rms(nudge * fit.motion) + 1e-15);
    }
  }
}

TEST(RigidFit, RejectsInputsThatDoNotDetermineAMotion) {
  const std::vector<Vec3<double>> two = {{0, 0, 0}, {1, 0, 0}};
  EXPECT_FALSE((fit_rigid_motion<double>(two, two).valid));

  const std::vector<Vec3<double>> three = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  const std::vector<Vec3<double>> four = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  EXPECT_FALSE((fit_rigid_motion<double>(three, four).valid));

  const std::vector<Vec3<double>> collinear = {{0, 0, 0}, {1, 1, 1}, {2, 2, 2}, {-3, -3, -3}};
  EXPECT_FALSE((fit_rigid_motion<double>(collinear, collinear).valid));

  const std::vector<Vec3<double>> coincident(4, Vec3<double>(1, 2, 3));
  EXPECT_FALSE((fit_rigid_motion<double>(coincident, coincident).valid));
}

TEST(RigidFit, FloatFitMatchesDouble) {
  Random rng(62);
  for (int i = 0; i < 200; ++i) {
    const DualQuat<double> motion = rng.pose(1);
    std::vector<Vec3<float>> from, to;
    for (int k = 0; k < 5; ++k) {
      const Vec3<double> x = rng.vec3(1);
      from.emplace_back(x);
      to.emplace_back(transform_point(motion, x));
    }
    const RigidFit<float> fit = fit_rigid_motion<float>(from, to);
    ASSERT_TRUE(fit.valid);
    EXPECT_SAME_POSE(DualQuat<double>(fit.motion), motion, 1e-5);
  }
}

}  // namespace
}  // namespace dqskin
