#include "dqskin/dual_quat.hpp"
#include "test_support.hpp"

#include <cmath>

namespace dqskin {
namespace {

using test::Random;

TEST(ExpLog, ExpInvertsLog) {
  Random rng(40);
  for (int i = 0; i < 2000; ++i) {
    const DualQuat<double> q = rng.pose();
    EXPECT_DUALQUAT_NEAR(exp(log(q)), q, 1e-12);
  }
}

TEST(ExpLog, LogInvertsExpForAnglesBelowPi) {
  Random rng(41);
  for (int i = 0; i < 2000; ++i) {
    const DualVec<double> x{glm::normalize(rng.vec3(1)) * rng.uniform(0, M_PI - 1e-3), rng.vec3(5)};
    const DualVec<double> back = log(exp(x));
    EXPECT_LE(glm::distance(back.real, x.real), 1e-12);
    EXPECT_LE(glm::distance(back.dual, x.dual), 1e-11);
  }
}

TEST(ExpLog, LogIsTheScrewTimesHalfTheDualAngle) {
  // log q = (l + εm)(θ + εd)/2 [Kavan §3; Pennestri eq. 47].
  Random rng(42);
  for (int i = 0; i < 500; ++i) {
    const DualQuat<double> q = rng.pose();
    const Screw<double> s = to_screw(q);
    const DualVec<double> x = log(q);
    EXPECT_LE(glm::distance(x.real, s.axis * (s.theta / 2)), 1e-12);
    EXPECT_LE(glm::distance(x.dual, s.axis * (s.d / 2) + s.moment * (s.theta / 2)), 1e-11);
  }
}

TEST(ExpLog, LogOfPureTranslationIsHalfTheTranslation) {
  const DualVec<double> x = log(from_rotation_translation(Quat<double>(1, 0, 0, 0), Vec3<double>(2, -4, 6)));
  EXPECT_EQ(x.real, Vec3<double>(0));
  EXPECT_LE(glm::distance(x.dual, Vec3<double>(1, -2, 3)), 1e-15);
  EXPECT_DUALQUAT_NEAR(exp(x), from_rotation_translation(Quat<double>(1, 0, 0, 0), Vec3<double>(2, -4, 6)), 1e-15);
}

TEST(ExpLog, LogIsContinuousThroughZeroAngle) {
  // As θ → 0 the log must tend to (θ/2 l, t/2), not blow up.
  const Vec3<double> axis = glm::normalize(Vec3<double>(1, 1, 0)), t(3, -1, 2);
  for (const double theta : {1e-2, 1e-5, 1e-8, 1e-11, 1e-14}) {
    const DualVec<double> x = log(from_rotation_translation(glm::angleAxis(theta, axis), t));
    EXPECT_LE(glm::distance(x.real, axis * (theta / 2)), 1e-15);
    EXPECT_LE(glm::distance(x.dual, t * 0.5), 2 * theta * glm::length(t)) << theta;
  }
}

TEST(ExpLog, PowerHasTheExponentLaws) {
  Random rng(43);
  for (int i = 0; i < 1000; ++i) {
    DualQuat<double> q = rng.pose();
    if (q.real.w < 0) q = -q;  // angle ≤ π, so q^a q^b = q^(a+b) holds without wrapping
    const double a = rng.uniform(-2, 2), b = rng.uniform(-2, 2);
    EXPECT_DUALQUAT_NEAR(pow(q, 0.0), identity<double>(), 1e-15);
    EXPECT_DUALQUAT_NEAR(pow(q, 1.0), q, 1e-12);
    EXPECT_DUALQUAT_NEAR(pow(q, -1.0), quat_conjugate(q), 1e-12);
    EXPECT_DUALQUAT_NEAR(pow(q, a) * pow(q, b), pow(q, a + b), 1e-11);
    EXPECT_DUALQUAT_NEAR(pow(pow(q, 0.5), 2.0), q, 1e-12);
  }
}

TEST(ExpLog, PowerScalesTheDualAngle) {
  // q^t = cos(tθ̂/2) + ŝ sin(tθ̂/2): the same axis, t times the angle and the translation [Kavan §3].
  Random rng(44);
  for (int i = 0; i < 500; ++i) {
    DualQuat<double> q = rng.pose();
    if (q.real.w < 0) q = -q;
    const double t = rng.uniform(0.05, 1);
    const Screw<double> s = to_screw(q), st = to_screw(pow(q, t));
    EXPECT_NEAR(st.theta, t * s.theta, 1e-12);
    EXPECT_NEAR(st.d, t * s.d, 1e-11);
    EXPECT_LE(glm::distance(st.axis, s.axis), 1e-12);
    EXPECT_LE(glm::distance(st.moment, s.moment), 1e-10 * (1 + glm::length(s.moment)));
  }
}

TEST(ExpLog, FloatMatchesDouble) {
  Random rng(45);
  for (int i = 0; i < 1000; ++i) {
    const DualQuat<double> q = rng.pose(1);
    const double t = rng.uniform(0, 1);
    EXPECT_DUALQUAT_NEAR(DualQuat<double>(pow(DualQuat<float>(q), float(t))), pow(q, t), 2e-6);
  }
}

}  // namespace
}  // namespace dqskin
