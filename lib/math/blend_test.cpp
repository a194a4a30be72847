// Property tests for blending rigid transformations: DLB, DIB, ScLERP, QLB and LBS [Kavan §4, appendix A],
// with the antipodality rule of docs/DESIGN.md §3.5. Every test draws its poses from a fixed seed, so each
// run sees the same inputs.
#include "dqskin/dual_quat.hpp"
#include "test_support.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <iostream>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

namespace dqskin {
namespace {

using test::Random;
using DQ = DualQuat<double>;
using Q = Quat<double>;
using V3 = Vec3<double>;
using V4 = glm::vec<4, double, glm::defaultp>;
using M4 = Mat4<double>;

constexpr double kPi = std::numbers::pi;
constexpr double kPoseTolerance = 1e-9;

constexpr double to_degrees(double angle) { return angle * 180.0 / kPi; }
constexpr double to_radians(double angle) { return angle * kPi / 180.0; }

// q in its shorter form (w ≥ 0), whose rotation angle is at most π.
DQ shorter(const DQ& q) { return q.real.w < 0 ? -q : q; }

// q flipped to the hemisphere of ref, as dlb and sclerp do before interpolating.
DQ to_hemisphere(const DQ& q, const DQ& ref) { return glm::dot(q.real, ref.real) < 0 ? -q : q; }

// Screw parameters of the relative pose p* x, taken in its shorter form.
Screw<double> relative_screw(const DQ& p, const DQ& x) { return to_screw(shorter(quat_conjugate(p) * x)); }

// Translation along the axis `along` of a screw: d·(l·along). Invariant under the sign of the dual
// quaternion (−q has −l and −d), so two screws on one line compare whichever way their axes point.
double translation_along(const Screw<double>& s, const V3& along) { return s.d * glm::dot(s.axis, along); }

bool all_finite(const DQ& q) {
  for (int i = 0; i < 4; ++i)
    if (!std::isfinite(q.real[i]) || !std::isfinite(q.dual[i])) return false;
  return true;
}

// q, after a failure with its value printed if any component is not finite.
DQ checked(const DQ& q) {
  if (!all_finite(q))
    ADD_FAILURE() << "non-finite result " << glm::to_string(q.real) << " + ε" << glm::to_string(q.dual);
  return q;
}

DQ dlb_of(const std::vector<DQ>& q, const std::vector<double>& w) { return checked(blend_dlb<double>(q, w)); }

DibResult<double> dib_of(const std::vector<DQ>& q, const std::vector<double>& w, const DibOptions& options = {}) {
  DibResult<double> result = blend_dib<double>(q, w, options);
  result.blend = checked(result.blend);
  return result;
}

// A uniformly random unit direction.
V3 random_direction(Random& rnd) {
  for (;;) {
    const V3 v = rnd.vec3(1);
    const double length = glm::length(v);
    if (length > 0.1 && length <= 1) return v / length;
  }
}

// A rotation by an angle uniform in [0, max_angle] about a uniformly random axis.
Q random_rotation_up_to(Random& rnd, double max_angle) {
  return glm::angleAxis(rnd.uniform(0, max_angle), random_direction(rnd));
}

// A random pose with either sign (q and −q are the same pose).
DQ random_signed_pose(Random& rnd) {
  const DQ q = rnd.pose();
  return rnd.uniform(0, 1) < 0.5 ? -q : q;
}

// Σ wᵢ log(b* qᵢ), each b* qᵢ in its shorter form: DIB's correction, zero at its fixed point.
DualVec<double> weighted_log_sum(const DQ& b, const std::vector<DQ>& q, const std::vector<double>& w) {
  DualVec<double> x;
  for (size_t i = 0; i < q.size(); ++i) {
    const DualVec<double> l = dqskin::log(shorter(quat_conjugate(b) * q[i]));
    x.real += w[i] * l.real;
    x.dual += w[i] * l.dual;
  }
  return x;
}

double max_abs(const DualVec<double>& x) {
  double m = 0;
  for (int i = 0; i < 3; ++i) m = std::max({m, std::abs(x.real[i]), std::abs(x.dual[i])});
  return m;
}

enum class Side { kLeft, kRight };

// blend(r qᵢ; w) = r blend(qᵢ; w) (left) or blend(qᵢ r; w) = blend(qᵢ; w) r (right), as the same pose, for
// n = 2..8 random poses and convex weights [Kavan §4].
template <typename Blend>
void expect_invariant(Side side, Blend blend, unsigned seed, int trials) {
  Random rnd(seed);
  for (int trial = 0; trial < trials && !::testing::Test::HasFailure(); ++trial) {
    const size_t n = 2 + static_cast<size_t>(trial) % 7;
    const DQ r = rnd.pose();
    std::vector<DQ> q, moved;
    for (size_t i = 0; i < n; ++i) {
      q.push_back(random_signed_pose(rnd));
      moved.push_back(side == Side::kLeft ? r * q.back() : q.back() * r);
    }
    const std::vector<double> w = rnd.convex_weights(n);
    const DQ b = blend(q, w);
    EXPECT_TRUE(is_unit(b, 1e-12)) << "trial " << trial;
    EXPECT_SAME_POSE(blend(moved, w), side == Side::kLeft ? r * b : b * r, kPoseTolerance)
        << "\n  trial " << trial << ", n = " << n;
  }
}

// ---------------------------------------------------------------------------------------------------
// Bi-invariance of DLB and DIB [Kavan §4].

TEST(BlendDlb, IsLeftInvariant) { expect_invariant(Side::kLeft, dlb_of, 101, 3000); }
TEST(BlendDlb, IsRightInvariant) { expect_invariant(Side::kRight, dlb_of, 102, 3000); }

// On such widely spread random poses DIB does not always converge (about 0.5% of these sets use up the 32
// corrections), but every correction is itself bi-invariant, so the result is too.
TEST(BlendDib, IsLeftInvariant) {
  expect_invariant(Side::kLeft, [](const auto& q, const auto& w) { return dib_of(q, w).blend; }, 103, 2000);
}
TEST(BlendDib, IsRightInvariant) {
  expect_invariant(Side::kRight, [](const auto& q, const auto& w) { return dib_of(q, w).blend; }, 104, 2000);
}

// ---------------------------------------------------------------------------------------------------
// ScLERP [Kavan §4, Lemma 2].

TEST(BlendScLerp, IsLeftInvariant) {
  Random rnd(201);
  for (int trial = 0; trial < 3000 && !HasFailure(); ++trial) {
    const DQ r = rnd.pose(), p = random_signed_pose(rnd), q = random_signed_pose(rnd);
    const double t = rnd.uniform(0, 1);
    EXPECT_SAME_POSE(checked(sclerp(r * p, r * q, t)), r * sclerp(p, q, t), kPoseTolerance) << "\n  t = " << t;
  }
}

TEST(BlendScLerp, IsRightInvariant) {
  Random rnd(202);
  for (int trial = 0; trial < 3000 && !HasFailure(); ++trial) {
    const DQ r = rnd.pose(), p = random_signed_pose(rnd), q = random_signed_pose(rnd);
    const double t = rnd.uniform(0, 1);
    EXPECT_SAME_POSE(checked(sclerp(p * r, q * r, t)), sclerp(p, q, t) * r, kPoseTolerance) << "\n  t = " << t;
  }
}

// The screw of p* ScLERP(t; p, q) is that of p* q with both its angle and its translation scaled by t:
// constant axis, constant speed [Kavan §4].
TEST(BlendScLerp, MovesAtConstantSpeedAlongAFixedScrew) {
  Random rnd(203);
  int checked = 0;
  for (int trial = 0; trial < 2000 && !HasFailure(); ++trial) {
    const DQ p = random_signed_pose(rnd), q = random_signed_pose(rnd);
    const Screw<double> whole = relative_screw(p, to_hemisphere(q, p));
    // The axis of a tiny rotation is ill-conditioned; such pairs are covered by the other tests.
    if (whole.theta < 0.1) continue;
    ++checked;
    const double moment_tolerance = 1e-9 * (1 + glm::length(whole.moment));
    for (const double t : {0.05, 0.25, 0.5, 0.75, 1.0, rnd.uniform(0.05, 1)}) {
      const Screw<double> s = relative_screw(p, sclerp(p, q, t));
      EXPECT_NEAR(s.theta, t * whole.theta, 1e-9) << "t = " << t;
      EXPECT_NEAR(s.d, t * whole.d, 1e-9 * (1 + std::abs(whole.d))) << "t = " << t;
      EXPECT_LE(glm::length(s.axis - whole.axis), 1e-9) << "t = " << t;
      EXPECT_LE(glm::length(s.moment - whole.moment), moment_tolerance) << "t = " << t;
    }
  }
  EXPECT_GT(checked, 1900);
}

// ScLERP never goes the long way round: p* ScLERP(t; p, q) stays in the hemisphere w ≥ 0, its angle is t
// times the shorter angle of p* q (≤ π), and −q gives the same path as q.
TEST(BlendScLerp, TakesTheShortestPath) {
  Random rnd(204);
  for (int trial = 0; trial < 2000 && !HasFailure(); ++trial) {
    const DQ p = rnd.pose();
    DQ q = rnd.pose();
    if (trial % 2 == 1 && glm::dot(p.real, q.real) > 0) q = -q;  // half the pairs start in opposite hemispheres
    const double shortest = relative_screw(p, q).theta;
    ASSERT_LE(shortest, kPi + 1e-12);

    const DQ end = checked(sclerp(p, q, 1.0));
    EXPECT_SAME_POSE(end, q, kPoseTolerance);
    EXPECT_LE(relative_screw(p, end).theta, kPi + 1e-12);
    EXPECT_NEAR(relative_screw(p, end).theta, shortest, 1e-9);
    for (const double t : {0.25, 0.5, 0.75}) {
      const DQ step = quat_conjugate(p) * sclerp(p, q, t);
      EXPECT_GE(step.real.w, -1e-12) << "t = " << t;
      EXPECT_NEAR(to_screw(shorter(step)).theta, t * shortest, 1e-9) << "t = " << t;
      EXPECT_SAME_POSE(checked(sclerp(p, -q, t)), checked(sclerp(p, q, t)), kPoseTolerance) << "t = " << t;
    }
  }
}

// ---------------------------------------------------------------------------------------------------
// DLB against ScLERP [Kavan §4]: both follow the screw of p* q, so only the angle and the translation
// along that screw differ, by less than 8.15° and 15% of the translation d of p* q.

struct DlbScLerpGap {
  double angle = 0;        // |θ_DLB − θ_ScLERP|, radians
  double translation = 0;  // |d_DLB − d_ScLERP| / |d(p* q)|
};

// The gap at t between DLB and ScLERP of p and q, where `whole` is the screw of p* q in p's hemisphere.
DlbScLerpGap gap_at(const DQ& p, const DQ& q, const Screw<double>& whole, double t) {
  const Screw<double> a = relative_screw(p, dlb(p, q, t));
  const Screw<double> b = relative_screw(p, sclerp(p, q, t));
  DlbScLerpGap gap;
  gap.angle = std::abs(a.theta - b.theta);
  gap.translation = std::abs(translation_along(a, whole.axis) - translation_along(b, whole.axis)) / std::abs(whole.d);
  return gap;
}

TEST(BlendDlb, StaysWithinKavanBoundsOfScLerp) {
  Random rnd(301);
  DlbScLerpGap worst;
  int samples = 0, skipped_no_translation = 0;
  for (int trial = 0; trial < 4000 && !HasFailure(); ++trial) {
    const DQ p = random_signed_pose(rnd), q = random_signed_pose(rnd);
    const Screw<double> whole = relative_screw(p, to_hemisphere(q, p));
    for (int k = 0; k < 4; ++k) {
      const double t = rnd.uniform(0, 1);
      ++samples;
      // Shortest path: DLB stays on the screw axis of p* q, as ScLERP does.
      const Screw<double> a = relative_screw(p, dlb(p, q, t));
      if (a.theta > 1e-3 && whole.theta > 1e-3) {
        EXPECT_LE(glm::length(glm::cross(a.axis, whole.axis)), 1e-8) << "t = " << t;
        EXPECT_LE(glm::length(a.moment * glm::dot(a.axis, whole.axis) - whole.moment),
                  1e-8 * (1 + glm::length(whole.moment)))
            << "t = " << t;
      }
      if (std::abs(whole.d) < 1e-6) {  // no translation along the axis to compare against
        ++skipped_no_translation;
        continue;
      }
      const DlbScLerpGap gap = gap_at(p, q, whole, t);
      EXPECT_LT(gap.angle, to_radians(8.15)) << "t = " << t << ", θ(p* q) = " << whole.theta;
      // The true supremum is 15.014% (see AttainsKavanBoundsAtAHalfTurn), reached only within ~0.1° of a
      // half turn and a narrow band of t; these seeded samples stay below the paper's rounded 15%.
      EXPECT_LT(gap.translation, 0.15) << "t = " << t << ", θ(p* q) = " << whole.theta;
      worst.angle = std::max(worst.angle, gap.angle);
      worst.translation = std::max(worst.translation, gap.translation);
    }
  }
  std::cout << "  DLB vs ScLERP over " << samples << " random samples (" << skipped_no_translation
            << " with |d| < 1e-6 skipped): max angle gap " << to_degrees(worst.angle) << "°, max translation gap "
            << 100 * worst.translation << "% of d\n";
  EXPECT_LT(skipped_no_translation, samples / 100);
}

// Kavan's bounds are the suprema over all relative poses, attained at a relative rotation of exactly
// 180° (the largest in p's hemisphere): there DLB's angle is 2 atan(t / (1 − t)) and its translation
// d t² / ((1 − t)² + t²), against ScLERP's π t and d t. The maxima are 8.149° (at t ≈ 0.239 and 0.761)
// and 15.014% of d (at t ≈ 0.257 and 0.743); the paper rounds them to "less than 8.15 degrees" and
// "less than 15%", so the translation bound is slightly exceeded at the very worst case.
TEST(BlendDlb, AttainsKavanBoundsAtAHalfTurn) {
  struct HalfTurn {
    V3 axis;
    V3 point;  // a point of the axis
    double d;  // translation along the axis
  };
  const HalfTurn cases[] = {
      {{1, 0, 0}, {0, 0, 0}, 1.0},
      {{0, 1, 0}, {2, 0, -1}, -0.3},
      {{0, 0, 1}, {0.5, 4, 0}, 7.0},
      {glm::normalize(V3(1, -2, 3)), {1, 1, 1}, 2.5},
  };
  for (const HalfTurn& c : cases) {
    // Relative to p = identity, so p* q = q; its w = cos(π/2) > 0 keeps q in p's hemisphere.
    const DQ p = identity<double>();
    const Screw<double> whole{kPi, c.d, c.axis, glm::cross(c.point, c.axis)};
    const DQ q = from_screw(whole);
    DlbScLerpGap worst;
    double worst_angle_t = 0, worst_translation_t = 0;
    constexpr int kSteps = 10000;
    for (int i = 0; i <= kSteps; ++i) {
      const double t = static_cast<double>(i) / kSteps;
      const DlbScLerpGap gap = gap_at(p, q, whole, t);
      if (gap.angle > worst.angle) {
        worst.angle = gap.angle;
        worst_angle_t = t;
      }
      if (gap.translation > worst.translation) {
        worst.translation = gap.translation;
        worst_translation_t = t;
      }
    }
    std::cout << "  half turn about " << glm::to_string(c.axis) << ": max angle gap " << to_degrees(worst.angle)
              << "° at t = " << worst_angle_t << ", max translation gap " << 100 * worst.translation
              << "% of d at t = " << worst_translation_t << "\n";
    EXPECT_GE(to_degrees(worst.angle), 8.10);
    EXPECT_LT(to_degrees(worst.angle), 8.15);
    EXPECT_GE(worst.translation, 0.1500);
    EXPECT_LE(worst.translation, 0.1502);
  }
}

// ---------------------------------------------------------------------------------------------------
// DIB [Kavan §4, Lemma 3].

// For two poses one correction of DLB already gives ScLERP, and the next correction is zero.
TEST(BlendDib, EqualsScLerpAfterOneCorrectionForTwoPoses) {
  Random rnd(401);
  int inexact_dlb = 0;
  for (int trial = 0; trial < 3000 && !HasFailure(); ++trial) {
    const DQ p = random_signed_pose(rnd), q = random_signed_pose(rnd);
    const double t = rnd.uniform(0, 1);
    const std::vector<DQ> poses{p, q};
    const std::vector<double> w{1 - t, t};
    const DQ expected = checked(sclerp(p, q, t));

    const DibResult<double> one = dib_of(poses, w, DibOptions{.precision = 1e-12, .max_iterations = 1});
    EXPECT_SAME_POSE(one.blend, expected, kPoseTolerance) << "\n  t = " << t;
    EXPECT_LE(one.iterations, 1);

    const DibResult<double> full = dib_of(poses, w);
    EXPECT_TRUE(full.converged) << "t = " << t;
    EXPECT_SAME_POSE(full.blend, expected, kPoseTolerance) << "\n  t = " << t;
    EXPECT_LE(full.iterations, 1) << "t = " << t;
    if (test::pose_diff(dlb(p, q, t), expected) > 1e-9) {
      ++inexact_dlb;
      EXPECT_EQ(full.iterations, 1) << "t = " << t;
    }
  }
  EXPECT_GT(inexact_dlb, 2500);  // the correction really was exercised
}

// Skinning-like inputs: the joints influencing one vertex have nearby poses, a common pose times small
// relative motions (rotations up to 75°, translations up to 0.5). DIB runs on 3000 such sets of 4
// influences with convex weights; every run must converge to the fixed point Σ wᵢ log(b* qᵢ) = 0.
struct DibRuns {
  std::vector<int> histogram;  // histogram[k]: runs that took k corrections
  int runs = 0;
  int max_iterations = 0;
  double worst_residual = 0;  // largest component of Σ wᵢ log(b* qᵢ) at the result

  int within(int lo, int hi) const {
    int count = 0;
    for (size_t k = 0; k < histogram.size(); ++k)
      if (static_cast<int>(k) >= lo && static_cast<int>(k) <= hi) count += histogram[k];
    return count;
  }
  std::string text() const {
    std::ostringstream out;
    for (size_t k = 0; k < histogram.size(); ++k) out << (k ? " " : "") << k << ":" << histogram[k];
    return out.str();
  }
};

DibRuns run_dib_on_skinning_inputs(const DibOptions& options, double residual_tolerance) {
  Random rnd(402);
  constexpr size_t kInfluences = 4;
  DibRuns runs;
  for (int run = 0; run < 3000 && !::testing::Test::HasFailure(); ++run) {
    const DQ common = rnd.pose();
    std::vector<DQ> q;
    for (size_t i = 0; i < kInfluences; ++i) {
      const DQ relative = from_rotation_translation(random_rotation_up_to(rnd, to_radians(75)),
                                                    rnd.uniform(0, 0.5) * random_direction(rnd));
      const DQ pose = common * relative;
      q.push_back(rnd.uniform(0, 1) < 0.5 ? -pose : pose);
    }
    const std::vector<double> w = rnd.convex_weights(kInfluences);
    const DibResult<double> result = dib_of(q, w, options);
    ++runs.runs;
    EXPECT_TRUE(result.converged) << "run " << run << " after " << result.iterations << " iterations";
    EXPECT_GE(result.iterations, 0) << "run " << run;
    EXPECT_TRUE(is_unit(result.blend, 1e-12)) << "run " << run;
    const size_t bin = static_cast<size_t>(std::max(result.iterations, 0));
    if (bin >= runs.histogram.size()) runs.histogram.resize(bin + 1, 0);
    ++runs.histogram[bin];
    runs.max_iterations = std::max(runs.max_iterations, result.iterations);
    const double residual = max_abs(weighted_log_sum(result.blend, q, w));
    runs.worst_residual = std::max(runs.worst_residual, residual);
    EXPECT_LE(residual, residual_tolerance) << "run " << run;
  }
  std::cout << "  DIB at precision " << options.precision << ", iterations over " << runs.runs
            << " runs (iterations:count): " << runs.text() << "\n  worst fixed-point residual "
            << runs.worst_residual << "\n";
  return runs;
}

// Kavan: DIB "converges very quickly, typically in 1 to 4 steps". That holds at the precision skinning
// needs (float, 1e-6): at least 95% of the runs take 1 to 4 corrections.
TEST(BlendDib, ConvergesInOneToFourIterationsAtFloatPrecision) {
  const DibRuns runs = run_dib_on_skinning_inputs(DibOptions{.precision = 1e-6, .max_iterations = 32}, 1e-6);
  RecordProperty("dib_iterations_histogram_1e-6", runs.text());
  EXPECT_EQ(runs.runs, 3000);
  EXPECT_GE(runs.within(1, 4), runs.runs * 95 / 100);
}

// At the default precision (1e-12) the iteration is linear, each correction about 100 times smaller than
// the last on these inputs, so it takes 2 to 11 corrections (6 most often): every run still converges, to
// the fixed point, well within the default 32 corrections.
TEST(BlendDib, ConvergesToTheFixedPointAtDefaultPrecision) {
  const DibRuns runs = run_dib_on_skinning_inputs(DibOptions{}, 1e-10);
  RecordProperty("dib_iterations_histogram_default", runs.text());
  EXPECT_EQ(runs.runs, 3000);
  EXPECT_LE(runs.max_iterations, 16);
  EXPECT_GE(runs.within(1, 8), runs.runs * 95 / 100);
}

// ---------------------------------------------------------------------------------------------------
// Antipodality (docs/DESIGN.md §3.5): inputs are flipped to the hemisphere of the largest weight.

TEST(BlendAntipodality, OppositeSignsOfOnePoseBlendToThatPose) {
  Random rnd(501);
  for (int trial = 0; trial < 500 && !HasFailure(); ++trial) {
    const DQ q = rnd.pose();
    const std::vector<DQ> pair{q, -q};
    EXPECT_SAME_POSE(dlb_of(pair, {0.5, 0.5}), q, 1e-12);
    // The result takes the sign of the input with the largest weight.
    EXPECT_DUALQUAT_NEAR(dlb_of(pair, {0.6, 0.4}), q, 1e-12);
    EXPECT_DUALQUAT_NEAR(dlb_of(pair, {0.4, 0.6}), -q, 1e-12);
  }
}

// Input signs other than the largest-weight input's change nothing; the result lies in that input's
// hemisphere.
TEST(BlendAntipodality, FollowsTheSignOfTheLargestWeight) {
  Random rnd(502);
  for (int trial = 0; trial < 2000 && !HasFailure(); ++trial) {
    const size_t n = 2 + static_cast<size_t>(trial) % 7;
    std::vector<DQ> q;
    for (size_t i = 0; i < n; ++i) q.push_back(random_signed_pose(rnd));
    const std::vector<double> w = rnd.convex_weights(n);
    const size_t largest = static_cast<size_t>(std::max_element(w.begin(), w.end()) - w.begin());
    const DQ b = dlb_of(q, w);
    EXPECT_GE(glm::dot(b.real, q[largest].real), 0.0);

    std::vector<DQ> flipped = q;
    for (size_t i = 0; i < n; ++i)
      if (i != largest && rnd.uniform(0, 1) < 0.5) flipped[i] = -flipped[i];
    EXPECT_DUALQUAT_NEAR(dlb_of(flipped, w), b, 1e-12);
    flipped[largest] = -flipped[largest];
    EXPECT_DUALQUAT_NEAR(dlb_of(flipped, w), -b, 1e-12);
    // DIB takes every b* qᵢ in its shorter form, so its pose does not depend on the signs either.
    EXPECT_SAME_POSE(dib_of(flipped, w).blend, dib_of(q, w).blend, kPoseTolerance);
  }
}

// The identity and a half turn about x (real parts orthogonal) blend at 0.5/0.5 to a quarter turn about
// x, not to NaN.
TEST(BlendAntipodality, HalfTurnAndIdentityBlendToAQuarterTurn) {
  const DQ half_turn = from_rotation_translation(Q(0.0, 1.0, 0.0, 0.0), V3(0));  // w, x, y, z
  for (const DQ& turn : {half_turn, -half_turn}) {
    const std::vector<DQ> poses{identity<double>(), turn};
    const DQ b = dlb_of(poses, {0.5, 0.5});
    ASSERT_TRUE(all_finite(b));
    const Screw<double> s = to_screw(shorter(b));
    EXPECT_NEAR(s.theta, kPi / 2, 1e-12);
    EXPECT_NEAR(std::abs(s.axis.x), 1, 1e-12);
    EXPECT_NEAR(s.d, 0, 1e-12);
    EXPECT_NEAR(glm::length(translation(b)), 0, 1e-12);
    const V3 y = transform_point(b, V3(0, 1, 0));
    EXPECT_NEAR(y.x, 0, 1e-12);
    EXPECT_NEAR(y.y, 0, 1e-12);
    EXPECT_NEAR(std::abs(y.z), 1, 1e-12);
  }
}

TEST(BlendAntipodality, IdentitiesBlendToIdentity) {
  Random rnd(503);
  for (size_t n = 1; n <= 8; ++n) {
    std::vector<DQ> q;
    for (size_t i = 0; i < n; ++i) q.push_back(i % 2 ? -identity<double>() : identity<double>());
    const std::vector<double> w = rnd.convex_weights(n);
    const DQ b = dlb_of(q, w);
    EXPECT_SAME_POSE(b, identity<double>(), 1e-15) << "n = " << n;
    EXPECT_SAME_POSE(dib_of(q, w).blend, identity<double>(), 1e-15) << "n = " << n;
  }
}

// Pure translations commute, and DLB blends them exactly: the weighted mean translation.
TEST(BlendAntipodality, PureTranslationsBlendToTheWeightedMean) {
  Random rnd(504);
  for (int trial = 0; trial < 1000 && !HasFailure(); ++trial) {
    const size_t n = 1 + static_cast<size_t>(trial) % 8;
    std::vector<DQ> q;
    std::vector<V3> t;
    for (size_t i = 0; i < n; ++i) {
      t.push_back(rnd.vec3(10));
      const DQ pose = from_rotation_translation(Q(1.0, 0.0, 0.0, 0.0), t.back());
      q.push_back(i % 3 == 1 ? -pose : pose);
    }
    const std::vector<double> w = rnd.convex_weights(n);
    V3 mean(0);
    for (size_t i = 0; i < n; ++i) mean += w[i] * t[i];
    const DQ expected = from_rotation_translation(Q(1.0, 0.0, 0.0, 0.0), mean);
    const DQ b = dlb_of(q, w);
    EXPECT_SAME_POSE(b, expected, 1e-12);
    EXPECT_LE(glm::length(translation(b) - mean), 1e-12);
    const DibResult<double> dib = dib_of(q, w);
    EXPECT_SAME_POSE(dib.blend, expected, 1e-12);
    EXPECT_EQ(dib.iterations, 0);  // DLB was already exact
  }
}

// ---------------------------------------------------------------------------------------------------
// QLB and LBS [Kavan §4, §6].

// DLB's real part is QLB of the rotations, whatever the translations.
TEST(BlendQlb, EqualsTheRealPartOfDlb) {
  Random rnd(601);
  for (int trial = 0; trial < 2000 && !HasFailure(); ++trial) {
    const size_t n = 1 + static_cast<size_t>(trial) % 8;
    std::vector<DQ> q;
    std::vector<Q> r;
    for (size_t i = 0; i < n; ++i) {
      q.push_back(random_signed_pose(rnd));
      r.push_back(q.back().real);
    }
    const std::vector<double> w = rnd.convex_weights(n);
    const Q qlb = blend_qlb<double>(r, w);
    const Q real = dlb_of(q, w).real;
    for (int k = 0; k < 4; ++k) EXPECT_NEAR(qlb[k], real[k], 1e-12) << "component " << k;
    EXPECT_NEAR(glm::length(qlb), 1, 1e-12);
  }
}

TEST(BlendLbs, EqualsTheWeightedSumOfMatrices) {
  Random rnd(701);
  for (int trial = 0; trial < 1000 && !HasFailure(); ++trial) {
    const size_t n = 1 + static_cast<size_t>(trial) % 8;
    std::vector<M4> m;
    for (size_t i = 0; i < n; ++i) m.push_back(to_rigid_matrix(rnd.pose()));
    const std::vector<double> w = rnd.convex_weights(n);
    M4 expected(0.0);
    for (size_t i = 0; i < n; ++i) expected += w[i] * m[i];
    const M4 blended = blend_lbs<double>(m, w);
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r) EXPECT_NEAR(blended[c][r], expected[c][r], 1e-12) << "[" << c << "][" << r << "]";
  }
}

// The candy-wrapper artifact [Kavan §6]: LBS of the identity and a half turn about x collapses the
// point (0, 1, 0) onto the axis, while DLB rotates it by a quarter turn, keeping its distance 1.
TEST(BlendLbs, CollapsesAHalfTurnWhereDlbKeepsTheDistance) {
  const DQ half_turn = from_rotation_translation(Q(0.0, 1.0, 0.0, 0.0), V3(0));
  const std::vector<M4> matrices{to_rigid_matrix(identity<double>()), to_rigid_matrix(half_turn)};
  const std::vector<DQ> poses{identity<double>(), half_turn};
  const std::vector<double> w{0.5, 0.5};

  const V4 lbs = blend_lbs<double>(matrices, w) * V4(0, 1, 0, 1);
  EXPECT_LE(glm::length(V3(lbs)), 1e-12) << glm::to_string(lbs);

  const V3 dq = transform_point(dlb_of(poses, w), V3(0, 1, 0));
  EXPECT_NEAR(std::hypot(dq.y, dq.z), 1.0, 1e-12) << glm::to_string(dq);
  EXPECT_NEAR(dq.x, 0, 1e-12);
}

// ---------------------------------------------------------------------------------------------------
// DLB edge cases.

TEST(BlendDlb, ReturnsASinglePoseUnchanged) {
  Random rnd(801);
  for (int trial = 0; trial < 500; ++trial) {
    const DQ q = random_signed_pose(rnd);
    EXPECT_DUALQUAT_NEAR(dlb_of({q}, {1.0}), q, 1e-12);
    EXPECT_DUALQUAT_NEAR(dlb_of({q}, {0.3}), q, 1e-12);
    const DibResult<double> dib = dib_of({q}, {1.0});
    EXPECT_SAME_POSE(dib.blend, q, 1e-12);
    EXPECT_EQ(dib.iterations, 0);
    if (HasFailure()) return;
  }
}

// Σ wᵢ qᵢ / ||Σ wᵢ qᵢ|| does not change when every weight is scaled: weights need not be normalised.
TEST(BlendDlb, IgnoresTheScaleOfTheWeights) {
  Random rnd(802);
  for (int trial = 0; trial < 2000 && !HasFailure(); ++trial) {
    const size_t n = 2 + static_cast<size_t>(trial) % 7;
    std::vector<DQ> q;
    for (size_t i = 0; i < n; ++i) q.push_back(random_signed_pose(rnd));
    const std::vector<double> w = rnd.convex_weights(n);
    std::vector<double> scaled = w;
    for (double& x : scaled) x *= 3;
    EXPECT_DUALQUAT_NEAR(dlb_of(q, scaled), dlb_of(q, w), 1e-12);
  }
}

// The float instantiation blends like the double one, to float precision.
TEST(BlendDlb, FloatAgreesWithDouble) {
  Random rnd(803);
  for (int trial = 0; trial < 500 && !HasFailure(); ++trial) {
    const size_t n = 1 + static_cast<size_t>(trial) % 8;
    std::vector<DQ> q;
    std::vector<DualQuat<float>> qf;
    for (size_t i = 0; i < n; ++i) {
      q.push_back(random_signed_pose(rnd));
      qf.push_back(DualQuat<float>(q.back()));
    }
    const std::vector<double> w = rnd.convex_weights(n);
    std::vector<float> wf;
    for (const double x : w) wf.push_back(static_cast<float>(x));
    const DQ expected = dlb_of(q, w);
    const DQ actual = checked(DQ(blend_dlb<float>(qf, wf)));
    EXPECT_SAME_POSE(actual, expected, 2e-5);
  }
}

}  // namespace
}  // namespace dqskin
