// The verdict rules on made-up summaries: each rule in its order, and the asset's choice among joints.
#include "verdict.hpp"

#include <gtest/gtest.h>

namespace dqskin::report_detail {
namespace {

struct Case {
  JointRegion region;
  JointData joint;
  std::vector<ClipData> clips;
  explicit Case(const char* name) {
    region.name = name;
    joint.region = &region;
    clips.emplace_back().name = "Walk";
  }
  Verdict judge(const ReportThresholds& t = {}) const { return joint_verdict(joint, clips, t, 1.0); }
};

TEST(Verdict, RulesInTheirOrder) {
  Case c("forearm");
  JointSummary& s = c.joint.summary;
  s.lbs_dib_max = 0.004, s.dqs_dib_max = 0.001;  // tolerance: 0.5 % of a diagonal of 1
  EXPECT_EQ(c.judge().code, "lbs-fine");
  s.lbs_dib_max = 0.05, s.twist_max = 170;
  EXPECT_EQ(c.judge().code, "add-twist-joints");
  EXPECT_NE(c.judge().text.find("forearm twists 170° in Walk"), std::string::npos) << c.judge().text;
  s.twist_max = 20, s.dqs_dib_max = 0.02, s.candy_wrapper = 0.5;
  EXPECT_EQ(c.judge().code, "use-dqs");
  EXPECT_NE(c.judge().text.find("candy-wrapper index 0.50"), std::string::npos) << c.judge().text;
  s.candy_wrapper = 0.1;
  s.dqs_dib_max = 0.004;  // within the tolerance where lbs is not
  EXPECT_EQ(c.judge().code, "use-dqs");
  s.dqs_dib_max = 0.02, s.dqs_bulge = 0.25;
  EXPECT_EQ(c.judge().code, "dqs-bulges");
  EXPECT_NE(c.judge().text.find("125 %"), std::string::npos) << c.judge().text;
  s.dqs_bulge = 0.05;
  EXPECT_EQ(c.judge().code, "dqs-closer");
  s.dqs_dib_max = 0.08;
  EXPECT_EQ(c.judge().code, "dqs-closer");
  EXPECT_EQ(c.judge().text.rfind("neither blend", 0), 0u) << c.judge().text;
  // An absolute tolerance.
  ReportThresholds t;
  t.tolerance = 0.1, t.tolerance_relative = false;
  EXPECT_EQ(c.judge(t).code, "lbs-fine");
}

TEST(Verdict, AssetTakesTheMostPressingCode) {
  Case a("hip"), b("knee"), c("wrist");
  a.joint.verdict = {"lbs-fine", "lbs is fine: hip", {"hip"}};
  b.joint.verdict = {"use-dqs", "use dqs: knee: lbs is off by up to 0.3", {"knee"}};
  c.joint.verdict = {"add-twist-joints", "add twist joints: wrist twists 170° in Walk", {"wrist"}};
  const Verdict v = asset_verdict({a.joint, b.joint, c.joint});
  EXPECT_EQ(v.code, "use-dqs");
  EXPECT_EQ(v.joints, std::vector<std::string>{"knee"});
  EXPECT_EQ(v.text, "use dqs: knee — knee: lbs is off by up to 0.3; also 1 joint add-twist-joints, 1 joint lbs-fine");
}

}  // namespace
}  // namespace dqskin::report_detail
