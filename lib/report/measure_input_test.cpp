// The report's measures on the project's rigs (testdata/, made by scripts/testdata/make_rigs.py), whose answers are
// known: the twisted cylinder's candy wrapper, the bending arm's elbow, the eight-influence chain.
#include "measure_input.hpp"

#include "../test_support/test_models.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace dqskin::report_detail {
namespace {

using testing_support::model_path;

struct Measured {
  std::vector<InputPlan> plans;
  InputData data;
};

Measured measure(const std::string& rig) {
  Measured m;
  PlanOptions plan;
  plan.out_dir = ::testing::TempDir();
  double seconds = 0;
  m.plans = plan_inputs({model_path(rig).string()}, plan, seconds);
  if (!m.plans.at(0).error.empty()) throw std::runtime_error(m.plans[0].error);
  ProgressCounter progress(0, {});
  m.data = measure_input(m.plans[0], ReportOptions{}, progress);
  return m;
}

const JointData& joint(const InputData& data, const std::string& name) {
  for (const JointData& j : data.joints)
    if (j.region->name == name) return j;
  throw std::runtime_error("no joint " + name);
}

TEST(MeasureInput, TwistedCylinderLbsCollapsesAtHalfTurnDqsKeepsItsSection) {
  const Measured m = measure("twisted_cylinder.gltf");
  const JointData& child = joint(m.data, "child");
  EXPECT_EQ(child.parent_name, "root");
  const std::vector<JointFrame>& frames = child.clips.at(0);
  ASSERT_EQ(m.data.clips.at(0).times.back(), 1.0);
  const JointFrame& last = frames.back();
  // The clip reaches a 180° turn of the child about its bone (+y): the 50/50 ring at y = 2 is averaged
  // with its own half-turned copy by lbs and collapses onto the axis; dqs turns it rigidly by 90°.
  EXPECT_NEAR(last.twist, 180.0, 1e-6);
  EXPECT_NEAR(last.bend, 0.0, 1e-3);
  EXPECT_LT(last.area_lbs, 1e-3);
  EXPECT_NEAR(last.area_dqs, 1.0, 1e-3);
  EXPECT_NEAR(last.area_dib, 1.0, 1e-3);
  // At rest nothing has moved.
  EXPECT_NEAR(frames.front().area_lbs, 1.0, 1e-6);
  EXPECT_NEAR(frames.front().twist, 0.0, 1e-9);
  EXPECT_NEAR(child.summary.candy_wrapper, 1.0, 1e-3);
  EXPECT_NEAR(child.summary.twist_max, 180.0, 1e-6);
  EXPECT_EQ(child.verdict.code, "add-twist-joints");
  EXPECT_NE(child.verdict.text.find("twists 180° in twist"), std::string::npos) << child.verdict.text;
  // The open tube has no volume; the root has no parent, so no section, twist or bend.
  EXPECT_FALSE(m.data.clips[0].volume.has_value());
  const JointData& root = joint(m.data, "root");
  EXPECT_TRUE(std::isnan(root.summary.candy_wrapper));
  EXPECT_TRUE(std::isnan(root.summary.twist_max));
}

TEST(MeasureInput, BendingArmElbowSectionAndBulge) {
  const Measured m = measure("bending_arm.gltf");
  const JointData& elbow = joint(m.data, "elbow");
  EXPECT_NEAR(elbow.summary.bend_max, 90.0, 1e-6);
  EXPECT_NEAR(elbow.summary.twist_max, 0.0, 1e-6);
  // lbs averages the 50/50 ring's two 90°-apart copies: flattened by cos 45° across the bend.
  EXPECT_NEAR(elbow.summary.area_lbs_min, std::sqrt(0.5), 1e-4);
  // dqs keeps the rings round; they only tilt against the mean axis, as dib's do (cos 22.5° for dib's
  // quarter-weight rings, DLB's lag a little more).
  EXPECT_GT(elbow.summary.area_dqs_min, 0.9);
  EXPECT_LT(elbow.summary.area_dqs_min, std::cos(glm::radians(22.5)));
  // The dqs bulge is measured. Every ring of this arm has one weight, so dqs and dib both move it
  // rigidly along the same screw (Kavan et al. §4: DLB differs from ScLERP only in the angle), and its
  // cross-section cannot grow past dib's: the bulge is zero to rounding.
  ASSERT_FALSE(std::isnan(elbow.summary.dqs_bulge));
  EXPECT_NEAR(elbow.summary.dqs_bulge, 0.0, 1e-6);
  // ...while dqs does stray from dib by DLB's angle error, far less than lbs.
  EXPECT_GT(elbow.summary.dqs_dib_max, 1e-3);
  EXPECT_LT(elbow.summary.dqs_dib_max * 10, elbow.summary.lbs_dib_max);
  EXPECT_EQ(elbow.verdict.code, "use-dqs");
}

TEST(MeasureInput, EightInfluencesAreCounted) {
  const Measured m = measure("eight_influences.gltf");
  EXPECT_EQ(m.data.max_influences, 8);
  EXPECT_EQ(m.data.joints.size(), 8u);
  const Measured four = measure("bending_arm.gltf");
  EXPECT_EQ(four.data.max_influences, 2);
}

}  // namespace
}  // namespace dqskin::report_detail
