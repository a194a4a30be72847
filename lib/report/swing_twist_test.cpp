// Swing–twist on rotations whose split is known.
#include "swing_twist.hpp"

#include <gtest/gtest.h>

namespace dqskin::report_detail {
namespace {

Quat<double> turn(double degrees, glm::dvec3 axis) { return glm::angleAxis(glm::radians(degrees), glm::normalize(axis)); }

TEST(SwingTwist, PureTwistIsAllTwist) {
  const SwingTwist st = swing_twist(turn(70, {0, 1, 0}), {0, 1, 0});
  EXPECT_NEAR(st.twist_degrees, 70, 1e-9);
  EXPECT_NEAR(st.swing_degrees, 0, 1e-6);
}

TEST(SwingTwist, PureSwingHasNoTwist) {
  const SwingTwist st = swing_twist(turn(35, {1, 0, 0}), {0, 1, 0});
  EXPECT_NEAR(st.twist_degrees, 0, 1e-9);
  EXPECT_NEAR(st.swing_degrees, 35, 1e-9);
}

TEST(SwingTwist, SwingAfterTwistIsSplitBack) {
  // q = swing · twist: a 120° twist about y, then a 40° swing about an axis normal to y.
  const Quat<double> q = turn(40, {1, 0, 1}) * turn(-120, {0, 1, 0});
  const SwingTwist st = swing_twist(q, {0, 1, 0});
  EXPECT_NEAR(st.twist_degrees, -120, 1e-9);
  EXPECT_NEAR(st.swing_degrees, 40, 1e-9);
}

TEST(SwingTwist, HalfTurnIsPlus180AndSignOfQuaternionDoesNotMatter) {
  const Quat<double> q = turn(180, {0, 0, 1});
  EXPECT_NEAR(swing_twist(q, {0, 0, 1}).twist_degrees, 180, 1e-9);
  EXPECT_NEAR(swing_twist(-q, {0, 0, 1}).twist_degrees, 180, 1e-9);
  const Quat<double> r = turn(-100, {0, 0, 1});
  EXPECT_NEAR(swing_twist(r, {0, 0, 1}).twist_degrees, -100, 1e-9);
  EXPECT_NEAR(swing_twist(-r, {0, 0, 1}).twist_degrees, -100, 1e-9);
}

TEST(SwingTwist, IdentityIsNothing) {
  const SwingTwist st = swing_twist(Quat<double>(1, 0, 0, 0), {0, 1, 0});
  EXPECT_EQ(st.twist_degrees, 0);
  EXPECT_EQ(st.swing_degrees, 0);
}

}  // namespace
}  // namespace dqskin::report_detail
