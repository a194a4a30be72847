#include "dqskin/dual_quat.hpp"
#include "test_support.hpp"

#include <cmath>
#include <vector>

namespace dqskin {
namespace {

using test::Random;

// Pennestri & Valentini Table 1 interpolates from the identity to a screw about the z axis through the
// origin: θ = 0.785398 (π/4) and d = 10. Their table lists, per t, the axis u, the translation d and θ.
const DualQuat<double> kStart = identity<double>();
const DualQuat<double> kEnd =
    from_rotation_translation(glm::angleAxis(M_PI / 4, Vec3<double>(0, 0, 1)), Vec3<double>(0, 0, 10));

struct TableRow {
  double t, d, theta;
};

void expect_row(const DualQuat<double>& q, const TableRow& row) {
  const Screw<double> s = to_screw(q);
  SCOPED_TRACE(testing::Message() << "t = " << row.t);
  EXPECT_NEAR(s.theta, row.theta, 1e-6);
  EXPECT_NEAR(s.d, row.d, 1e-6);
  EXPECT_LE(glm::distance(translation(q), Vec3<double>(0, 0, row.d)), 1e-6);
  if (row.theta > 0) {
    EXPECT_LE(glm::distance(s.axis, Vec3<double>(0, 0, 1)), 1e-12);  // u = {0, 0, 1}
  }
}

TEST(PennestriTable1, ScLerp) {
  const TableRow rows[] = {{0, 0, 0.000000},        {0.2, 2, 0.157080}, {0.4, 4, 0.314159},
                           {0.6, 6, 0.471239},      {0.8, 8, 0.628319}, {1.0, 10, 0.785398}};
  for (const TableRow& row : rows) expect_row(sclerp(kStart, kEnd, row.t), row);
}

TEST(PennestriTable1, SimpleDualQuaternionLinearBlending) {
  // sDLB [Pennestri Alg. 1]: the two-pose DLB.
  const TableRow rows[] = {{0, 0, 0.000000},           {0.2, 1.925100, 0.155128}, {0.4, 3.962077, 0.313176},
                           {0.6, 6.037923, 0.472222},  {0.8, 8.074900, 0.630270}, {1.0, 10, 0.785398}};
  for (const TableRow& row : rows) expect_row(dlb(kStart, kEnd, row.t), row);
}

// The DLB and DIB tables interpolate through three prescribed poses at t = 0, 0.5, 1 (the bold rows: the
// middle one is the screw halfway, θ = π/8, d = 5) with Lagrange weights [Pennestri eq. 34].
std::vector<double> lagrange_weights(double t) {
  const double nodes[3] = {0, 0.5, 1};
  std::vector<double> w(3, 1.0);
  for (int j = 0; j < 3; ++j)
    for (int k = 0; k < 3; ++k)
      if (k != j) w[size_t(j)] *= (t - nodes[k]) / (nodes[j] - nodes[k]);
  return w;
}

const DualQuat<double> kPrescribed[3] = {
    kStart, from_rotation_translation(glm::angleAxis(M_PI / 8, Vec3<double>(0, 0, 1)), Vec3<double>(0, 0, 5)), kEnd};

TEST(PennestriTable1, DualQuaternionLinearBlendingWithLagrangeWeights) {
  // [Pennestri Alg. 2, eq. 33-34]
  const TableRow rows[] = {{0, 0, 0.000000},          {0.2, 2.036640, 0.158043}, {0.4, 4.018432, 0.314643},
                           {0.5, 5, 0.392699},        {0.6, 5.981568, 0.470756}, {0.8, 7.963360, 0.627355},
                           {1.0, 10, 0.785398}};
  for (const TableRow& row : rows) expect_row(blend_dlb<double>(kPrescribed, lagrange_weights(row.t)), row);
}

TEST(PennestriTable1, DualQuaternionIterativeBlending) {
  // [Pennestri Alg. 3]. The paper prints d = 1.999999, 4.000002, 5.999998, 8.000001: noise of its own
  // iteration of up to 2e-6. The exact DIB answer for these coaxial poses is the ScLERP row (the paper
  // says so; Kavan's Lemma 3 argument applies since coaxial screws commute), so every row is checked
  // against the exact value to 1e-9, and against the printed value to 1e-6 in θ and 2.5e-6 in d.
  const TableRow rows[] = {{0, 0, 0.000000},        {0.2, 1.999999, 0.157080}, {0.4, 4.000002, 0.314159},
                           {0.5, 5, 0.392699},      {0.6, 5.999998, 0.471239}, {0.8, 8.000001, 0.628318},
                           {1.0, 10, 0.785398}};
  for (const TableRow& row : rows) {
    SCOPED_TRACE(testing::Message() << "t = " << row.t);
    const DibResult<double> dib = blend_dib<double>(kPrescribed, lagrange_weights(row.t));
    ASSERT_TRUE(dib.converged);
    const Screw<double> s = to_screw(dib.blend);
    EXPECT_NEAR(s.theta, row.t * M_PI / 4, 1e-9);
    EXPECT_NEAR(s.d, row.t * 10, 1e-9);
    EXPECT_NEAR(s.theta, row.theta, 1e-6);
    EXPECT_NEAR(s.d, row.d, 2.5e-6);
    EXPECT_SAME_POSE(dib.blend, sclerp(kStart, kEnd, row.t), 1e-9);
  }
}

TEST(ScLerp, EndpointsAreTheInputs) {
  Random rng(50);
  for (int i = 0; i < 500; ++i) {
    const DualQuat<double> p = rng.pose(), q = rng.pose();
    EXPECT_DUALQUAT_NEAR(sclerp(p, q, 0.0), p, 1e-12);
    EXPECT_SAME_POSE(sclerp(p, q, 1.0), q, 1e-11);
    EXPECT_DUALQUAT_NEAR(dlb(p, q, 0.0), p, 1e-12);
    EXPECT_SAME_POSE(dlb(p, q, 1.0), q, 1e-12);
  }
}

TEST(ScLerp, TakesTheShortWayWhateverTheSignOfTheInput) {
  Random rng(51);
  for (int i = 0; i < 500; ++i) {
    const DualQuat<double> p = rng.pose(), q = rng.pose();
    const double t = rng.uniform(0, 1);
    EXPECT_SAME_POSE(sclerp(p, -q, t), sclerp(p, q, t), 1e-11);
    EXPECT_SAME_POSE(dlb(p, -q, t), dlb(p, q, t), 1e-12);
    EXPECT_LE(to_screw(quat_conjugate(p) * sclerp(p, q, 1.0)).theta, M_PI + 1e-9);
  }
}

TEST(SepLerp, InterpolatesRotationAndTranslationSeparately) {
  // [Kenwright eq. 3]: the translation moves on a straight line, the rotation by SLERP.
  Random rng(52);
  for (int i = 0; i < 500; ++i) {
    const DualQuat<double> p = rng.pose(), q = rng.pose();
    const double t = rng.uniform(0, 1);
    const DualQuat<double> s = sep_lerp(p, q, t);
    EXPECT_LE(glm::distance(translation(s), glm::mix(translation(p), translation(q), t)), 1e-11);
    EXPECT_NEAR(std::abs(glm::dot(s.real, glm::slerp(p.real, q.real, t))), 1.0, 1e-12);
    EXPECT_TRUE(is_unit(s, 1e-12));
  }
}

TEST(SepLerp, DiffersFromScLerpWhenRotationAndTranslationCouple) {
  // A quarter turn about an axis away from the origin: ScLERP's path of the origin is an arc, SEP's a chord.
  const DualQuat<double> p = identity<double>();
  const DualQuat<double> q = from_screw(Screw<double>{M_PI / 2, 0, {0, 0, 1}, glm::cross(Vec3<double>(1, 0, 0), Vec3<double>(0, 0, 1))});
  const Vec3<double> arc = translation(sclerp(p, q, 0.5)), chord = translation(sep_lerp(p, q, 0.5));
  const Vec3<double> centre(1, 0, 0);
  EXPECT_NEAR(glm::distance(arc, centre), 1.0, 1e-12);       // on the circle about the axis
  EXPECT_LT(glm::distance(chord, centre), 1.0 - 0.25);        // inside it: cos 45° ≈ 0.707
}

TEST(KenLerp, BiasZeroIsSepLerpOneIsScLerp) {
  Random rng(53);
  for (int i = 0; i < 500; ++i) {
    const DualQuat<double> p = rng.pose(), q = rng.pose();
    const double t = rng.uniform(0, 1);
    EXPECT_SAME_POSE(ken_lerp(p, q, t, 0.0), sep_lerp(p, q, t), 1e-11);
    EXPECT_SAME_POSE(ken_lerp(p, q, t, 1.0), sclerp(p, q, t), 1e-11);
  }
}

TEST(KenLerp, BiasAboveOneAmplifiesTheCoupling) {
  // The translation keeps moving from SEP(LERP) through ScLERP and beyond; the rotation is the SLERP
  // at every bias, because ScLERP's rotation is SLERP's.
  Random rng(54);
  for (int i = 0; i < 500; ++i) {
    const DualQuat<double> p = rng.pose(), q = rng.pose();
    const double t = rng.uniform(0, 1), beta = rng.uniform(0, 3);
    const DualQuat<double> k = ken_lerp(p, q, t, beta);
    const Vec3<double> sep = translation(sep_lerp(p, q, t)), sc = translation(sclerp(p, q, t));
    EXPECT_LE(glm::distance(translation(k), sep + beta * (sc - sep)), 1e-10);
    EXPECT_NEAR(std::abs(glm::dot(k.real, glm::slerp(p.real, q.real, t))), 1.0, 1e-12);
  }
}

}  // namespace
}  // namespace dqskin
