#include "dqskin/dual_quat.hpp"
#include "test_support.hpp"

#include <cmath>

namespace dqskin {
namespace {

using test::Random;

bool finite(const Screw<double>& s) {
  return std::isfinite(s.theta) && std::isfinite(s.d) && std::isfinite(s.axis.x) && std::isfinite(s.axis.y) &&
         std::isfinite(s.axis.z) && std::isfinite(s.moment.x) && std::isfinite(s.moment.y) &&
         std::isfinite(s.moment.z);
}

TEST(Screw, PennestriExampleTranslateThenRotate) {
  // [Pennestri §2, numerical example]: translate by (2, 2, 1), then rotate 90° about the body's z axis.
  // Q̂ = (1.4142 − ε0.7071) + ε2.8284 i + (1.4142 + ε0.7071) k for the unnormalised 2× form (eq. 11).
  const DualQuat<double> q =
      from_rotation_translation(glm::angleAxis(M_PI / 2, Vec3<double>(0, 0, 1)), Vec3<double>(2, 2, 1));
  EXPECT_DUALQUAT_NEAR(q * 2.0, DualQuat<double>(Quat<double>(std::sqrt(2.0), 0, 0, std::sqrt(2.0)),
                                                 Quat<double>(-std::sqrt(0.5), 2 * std::sqrt(2.0), 0, std::sqrt(0.5))),
                       1e-12);

  // θ̂ = 1.570796 + ε·1, ĥ = k + ε 2i, the axis through (0, 2, 0), translation 1 along it.
  const Screw<double> s = to_screw(q);
  EXPECT_NEAR(s.theta, 1.570796, 1e-6);
  EXPECT_NEAR(s.d, 1.0, 1e-12);
  EXPECT_LE(glm::distance(s.axis, Vec3<double>(0, 0, 1)), 1e-12);
  EXPECT_LE(glm::distance(s.moment, Vec3<double>(2, 0, 0)), 1e-12);
  EXPECT_LE(glm::distance(point_on_axis(s), Vec3<double>(0, 2, 0)), 1e-12);
}

TEST(Screw, ScrewMotionMovesPointsAsRotationAboutTheAxisPlusSlide) {
  // Chasles: q(x) = p + R(x − p) + d l for the axis point p [Kavan Fig. 2].
  Random rng(30);
  for (int i = 0; i < 1000; ++i) {
    const DualQuat<double> q = rng.pose();
    const Screw<double> s = to_screw(q);
    const Vec3<double> p = point_on_axis(s);
    const Vec3<double> x = rng.vec3(5);
    const Vec3<double> expected = p + glm::angleAxis(s.theta, s.axis) * (x - p) + s.d * s.axis;
    EXPECT_LE(glm::distance(transform_point(q, x), expected), 1e-9 * (1 + glm::length(p)));
  }
}

TEST(Screw, DualQuaternionScrewRoundTripIsExactToDoubleRounding) {
  Random rng(31);
  for (int i = 0; i < 2000; ++i) {
    const DualQuat<double> q = rng.pose();
    EXPECT_DUALQUAT_NEAR(from_screw(to_screw(q)), q, 1e-12);
  }
}

TEST(Screw, DualQuaternionScrewRoundTripIsExactToFloatRounding) {
  Random rng(32);
  for (int i = 0; i < 2000; ++i) {
    const DualQuat<float> q(rng.pose(1));
    EXPECT_DUALQUAT_NEAR(from_screw(to_screw(q)), q, 1e-6f);
  }
}

Screw<double> random_screw(Random& rng, double theta) {
  Screw<double> s;
  s.theta = theta;
  s.d = rng.uniform(-5, 5);
  s.axis = glm::normalize(rng.vec3(1));
  const Vec3<double> p = rng.vec3(3);
  s.moment = glm::cross(p, s.axis);
  return s;
}

void expect_screw_near(const Screw<double>& a, const Screw<double>& b, double tol) {
  EXPECT_NEAR(a.theta, b.theta, tol);
  EXPECT_NEAR(a.d, b.d, tol);
  EXPECT_LE(glm::distance(a.axis, b.axis), tol);
  EXPECT_LE(glm::distance(a.moment, b.moment), tol * (1 + glm::length(b.moment)));
}

TEST(Screw, ScrewDualQuaternionRoundTripIsExactToDoubleRounding) {
  Random rng(33);
  for (int i = 0; i < 2000; ++i) {
    const Screw<double> s = random_screw(rng, rng.uniform(0.01, 2 * M_PI - 0.01));
    expect_screw_near(to_screw(from_screw(s)), s, 1e-12);
  }
}

TEST(Screw, ScrewDualQuaternionRoundTripIsExactToFloatRounding) {
  // The moment comes back through cot(θ/2) t⊥, so its rounding grows like 1/sin(θ/2): a float dual
  // quaternion holds the moment to 1e-6 only while sin(θ/2) ≥ 1/2. The double test covers every angle.
  Random rng(34);
  for (int i = 0; i < 2000; ++i) {
    const Screw<double> d = random_screw(rng, rng.uniform(M_PI / 3, 5 * M_PI / 3));
    const Screw<float> s{float(d.theta), float(d.d), Vec3<float>(d.axis), Vec3<float>(d.moment)};
    const Screw<float> back = to_screw(from_screw(s));
    EXPECT_NEAR(back.theta, s.theta, 1e-6f);
    EXPECT_NEAR(back.d, s.d, 2e-6f);  // |d| ≤ 5: 1e-6 relative
    EXPECT_LE(glm::distance(back.axis, s.axis), 1e-6f);
    EXPECT_LE(glm::distance(back.moment, s.moment), 1e-6f * (1 + glm::length(s.moment)));
  }
}

TEST(Screw, PureTranslationHasZeroAngleAndTheTranslationAsAxis) {
  const DualQuat<double> q = from_rotation_translation(Quat<double>(1, 0, 0, 0), Vec3<double>(0, 3, 4));
  const Screw<double> s = to_screw(q);
  EXPECT_EQ(s.theta, 0.0);
  EXPECT_NEAR(s.d, 5.0, 1e-15);
  EXPECT_LE(glm::distance(s.axis, Vec3<double>(0, 0.6, 0.8)), 1e-15);
  EXPECT_EQ(s.moment, Vec3<double>(0));
  EXPECT_DUALQUAT_NEAR(from_screw(s), q, 1e-15);
}

TEST(Screw, IdentityHasAFiniteScrew) {
  const Screw<double> s = to_screw(identity<double>());
  EXPECT_TRUE(finite(s));
  EXPECT_EQ(s.theta, 0.0);
  EXPECT_EQ(s.d, 0.0);
  EXPECT_DUALQUAT_NEAR(from_screw(s), identity<double>(), 0.0);
}

TEST(Screw, AnglesNearZeroAndNearTwoPiStayFiniteAndRoundTrip) {
  // Tiny rotations with a translation across the axis put the axis far away (|m| ~ 1/θ), but every
  // parameter stays finite and the pose survives the round trip.
  Random rng(35);
  for (const double theta : {1e-3, 1e-6, 1e-9, 1e-12, 2 * M_PI - 1e-3, 2 * M_PI - 1e-6, 2 * M_PI - 1e-9}) {
    for (int i = 0; i < 100; ++i) {
      const Vec3<double> axis = glm::normalize(rng.vec3(1));
      const DualQuat<double> q = from_rotation_translation(glm::angleAxis(theta, axis), rng.vec3(5));
      const Screw<double> s = to_screw(q);
      ASSERT_TRUE(finite(s)) << "theta " << theta;
      EXPECT_NEAR(s.theta, theta, 1e-9);
      EXPECT_DUALQUAT_NEAR(from_screw(s), q, 1e-9);
      for (int k = 0; k < 100; ++k) {  // the point motion agrees too
        const Vec3<double> x = rng.vec3(2);
        EXPECT_LE(glm::distance(transform_point(from_screw(s), x), transform_point(q, x)), 1e-8);
      }
    }
  }
}

TEST(Screw, RotationOfExactlyTwoPiIsHandledAsTranslation) {
  // −(pure translation) has w = −1 and no axis: θ = 2π, still finite.
  const DualQuat<double> q = -from_rotation_translation(Quat<double>(1, 0, 0, 0), Vec3<double>(1, 0, 0));
  const Screw<double> s = to_screw(q);
  EXPECT_TRUE(finite(s));
  EXPECT_NEAR(s.theta, 2 * M_PI, 1e-15);
  EXPECT_NEAR(s.d, 1.0, 1e-15);
}

}  // namespace
}  // namespace dqskin
