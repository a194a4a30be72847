// `diff --approve`: which goldens an approval replaces or adds, that it copies the candidates byte for
// byte, and that it replaces all of them or none.
#include "dqskin/diff_report.hpp"
#include "dqskin/error.hpp"
#include "dqskin/golden_approval.hpp"
#include "../test_support/read_file.hpp"
#include "../test_support/image_diff_fixture_oiio.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>

namespace dqskin {
namespace {

namespace fs = std::filesystem;
using testing_support::read_file;

class GoldenApprovalTest : public ImageDiffTest {
protected:
  // golden/ and out/: same.png equal, changed.png and sub/changed.png differ, warn.png a little, new.png
  // only in out/, gone.png only in golden/, broken.png unreadable in out/, lost.png unreadable in golden/.
  void SetUp() override {
    for (const char* side : {"golden", "out"}) {
      const std::string s = side;
      image(s + "/same.png", 4, 4, 3, 0.5f);
      image(s + "/warn.png", 4, 4, 3, s == "out" ? 0.502f : 0.5f);
    }
    image("golden/changed.png", 4, 4, 3, 0.5f);
    image("out/changed.png", 4, 4, 3, 0.9f);
    image("golden/sub/changed.png", 4, 4, 3, 0.1f);
    image("out/sub/changed.png", 4, 4, 3, 0.2f);
    image("out/new.png", 4, 4, 3, 0.3f);
    image("golden/gone.png", 4, 4, 3, 0.3f);
    image("golden/broken.png", 4, 4, 3, 0.3f);
    text_file("out/broken.png", "not a PNG");
    text_file("golden/lost.png", "not a PNG either");
    image("out/lost.png", 4, 4, 3, 0.7f);
  }

  DiffReport diff() const {
    DiffOptions o;
    o.thresholds.fail = 0.05;  // warn.png only warns
    o.thresholds.warn = 0.001;
    return diff_images(path("golden"), path("out"), o);
  }
};

TEST_F(GoldenApprovalTest, FailingPairsWithAReadableCandidateAreApproved) {
  const std::vector<Approval> list = approvals(diff());
  std::vector<std::string> names;
  for (const Approval& a : list) names.push_back(a.name + (a.added ? " (added)" : ""));
  EXPECT_EQ(names, (std::vector<std::string>{"changed.png", "lost.png", "new.png (added)", "sub/changed.png"}));
  EXPECT_EQ(list[2].golden, path("golden/new.png"));
  EXPECT_EQ(list[2].candidate, path("out/new.png"));
}

TEST_F(GoldenApprovalTest, ApprovedGoldensAreTheCandidatesBytesAndThenPass) {
  const std::string old_gone = read_file(path("golden/gone.png"));
  approve(approvals(diff()));
  for (const char* name : {"changed.png", "sub/changed.png", "new.png", "lost.png"})
    EXPECT_EQ(read_file(path(std::string("golden/") + name)), read_file(path(std::string("out/") + name))) << name;
  EXPECT_EQ(read_file(path("golden/gone.png")), old_gone);  // no candidate: kept
  const DiffReport after = diff();
  for (const ImageDiff& d : after.pairs)
    if (d.name != "gone.png" && d.name != "broken.png" && d.name != "warn.png") {
      EXPECT_EQ(d.status, DiffStatus::kPass) << d.name;
    }
  for (const auto& e : fs::recursive_directory_iterator(path("golden")))
    EXPECT_NE(e.path().filename().string()[0], '.') << "left behind: " << e.path();
}

TEST_F(GoldenApprovalTest, AllOrNone) {
  // The last golden's folder cannot be made (a file is in the way): the goldens already replaced are put
  // back and nothing else is left behind.
  std::vector<Approval> list = approvals(diff());
  const std::string before = read_file(path("golden/changed.png"));
  text_file("golden/blocked", "a file where a folder would go");
  list.push_back({"blocked/x.png", path("golden/blocked/x.png"), path("out/changed.png"), true});
  EXPECT_THROW(approve(list), OutputError);
  EXPECT_EQ(read_file(path("golden/changed.png")), before);
  EXPECT_FALSE(fs::exists(path("golden/new.png")));
  for (const auto& e : fs::recursive_directory_iterator(path("golden")))
    EXPECT_NE(e.path().filename().string()[0], '.') << "left behind: " << e.path();
}

TEST_F(GoldenApprovalTest, ReportsSayWhatWasApprovedAndTheVerdictAfter) {
  DiffReport report = diff();
  report.approval = true;
  report.approval_dry_run = true;
  report.approved = approvals(report);
  EXPECT_EQ(report.status(), DiffStatus::kFail);
  EXPECT_EQ(report.status_after_approval(), DiffStatus::kFail);  // gone.png and broken.png stay failing
  const std::string text = diff_text(report);
  EXPECT_NE(text.find("approved: would replace " + path("golden/changed.png") + " with " + path("out/changed.png") + "\n"),
            std::string::npos) << text;
  EXPECT_NE(text.find("approved: would add " + path("golden/new.png") + " from "), std::string::npos) << text;
  EXPECT_NE(text.find("approved: 4 goldens would be replaced or added (dry run: nothing changed); then FAIL\n"),
            std::string::npos) << text;
  const nlohmann::json doc = nlohmann::json::parse(diff_json(report));
  EXPECT_EQ(doc["approval"]["dry_run"], true);
  EXPECT_EQ(doc["approval"]["files"].size(), 4u);
  EXPECT_EQ(doc["approval"]["files"][2]["added"], true);
  EXPECT_EQ(doc["approval"]["status_after"], "FAIL");
}

}  // namespace
}  // namespace dqskin
