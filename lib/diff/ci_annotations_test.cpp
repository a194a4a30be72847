// The CI formats against their published descriptions: GitHub's workflow commands (docs.github.com,
// "Workflow commands for GitHub Actions"; escaping as actions/toolkit's command.ts), its step summary
// (GitHub-flavoured Markdown), and GitLab's Code Quality report (docs.gitlab.com, "Code Quality": an array
// of issues, each with description, check_name, fingerprint, severity in info|minor|major|critical|blocker
// and location.path with location.lines.begin).
#include "dqskin/ci_annotations.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <set>

namespace dqskin {
namespace {

using nlohmann::json;

std::vector<CiRow> rows() {
  return {{DiffStatus::kPass, "same.png", "out/same.png", "max 0, mean 0", ""},
          {DiffStatus::kFail, "a:b,c%d.png", "out/a:b,c%d.png", "max 0.5, mean 0.1", "3 pixels over --fail 0.01\nsecond line"},
          {DiffStatus::kWarn, "sub/w.png", "out/sub/w.png", "max 0.02, mean 0.001", "max error 0.02 over --hardwarn 0.01"},
          {DiffStatus::kFail, "gone.png", "golden/gone.png", "", "missing in B, only in A"}};
}

TEST(CiAnnotations, GithubCommandsOnePerFailingOrWarningRowEscaped) {
  EXPECT_EQ(github_annotations(rows()),
            "::error file=out/a%3Ab%2Cc%25d.png,title=dqskin diff%3A a%3Ab%2Cc%25d.png::3 pixels over --fail 0.01%0Asecond "
            "line (max 0.5, mean 0.1)\n"
            "::warning file=out/sub/w.png,title=dqskin diff%3A sub/w.png::max error 0.02 over --hardwarn 0.01 (max 0.02, "
            "mean 0.001)\n"
            "::error file=golden/gone.png,title=dqskin diff%3A gone.png::missing in B, only in A\n");
  EXPECT_EQ(github_annotations({rows()[0]}), "");
}

TEST(CiAnnotations, StepSummaryListsFailuresFirstInATable) {
  const std::string md = github_step_summary("dqskin diff golden out", DiffStatus::kFail, rows());
  EXPECT_EQ(md.substr(0, md.find("| |")), "### dqskin diff golden out: FAIL\n\n1 pass, 1 warn, 2 fail\n\n");
  const size_t fail1 = md.find("| FAIL | a:b,c%d.png"), fail2 = md.find("| FAIL | gone.png"),
               warn = md.find("| WARN | sub/w.png"), pass = md.find("| PASS | same.png");
  ASSERT_NE(fail1, std::string::npos) << md;
  EXPECT_LT(fail1, fail2);
  EXPECT_LT(fail2, warn);
  EXPECT_LT(warn, pass);
  // A line break inside a cell would end the table's row; a '|' would end the cell.
  EXPECT_NE(md.find("0.01 second line |"), std::string::npos) << md;
  const std::string piped = github_step_summary("t", DiffStatus::kFail, {{DiffStatus::kFail, "a|b", "f", "", "r"}});
  EXPECT_NE(piped.find("| a\\|b |"), std::string::npos) << piped;
  // A file name that reads as a link or an image stays text.
  const std::string linked = github_step_summary("t", DiffStatus::kFail, {{DiffStatus::kFail, "![x](http://e/y).png", "f", "", "r"}});
  EXPECT_NE(linked.find("| \\!\\[x\\](http://e/y).png |"), std::string::npos) << linked;
}

TEST(CiAnnotations, GitlabCodeQualityHasTheRequiredFields) {
  const json report = json::parse(gitlab_code_quality(rows()));
  ASSERT_TRUE(report.is_array());
  ASSERT_EQ(report.size(), 3u);  // the passing row is no issue
  const std::set<std::string> severities{"info", "minor", "major", "critical", "blocker"};
  std::set<std::string> fingerprints;
  for (const json& issue : report) {
    EXPECT_TRUE(issue["description"].is_string());
    EXPECT_EQ(issue["check_name"], "dqskin-diff");
    EXPECT_TRUE(severities.count(issue["severity"].get<std::string>()));
    EXPECT_TRUE(issue["location"]["path"].is_string());
    EXPECT_EQ(issue["location"]["lines"]["begin"], 1);
    fingerprints.insert(issue["fingerprint"].get<std::string>());
  }
  EXPECT_EQ(fingerprints.size(), 3u);
  EXPECT_EQ(report[0]["severity"], "major");
  EXPECT_EQ(report[1]["severity"], "minor");
  EXPECT_EQ(report[0]["location"]["path"], "out/a:b,c%d.png");
  // The same problem with other figures keeps its fingerprint; another verdict does not.
  std::vector<CiRow> later = rows();
  later[1].figures = "max 0.6, mean 0.2";
  later[1].reason = "4 pixels over --fail 0.01";
  later[2].status = DiffStatus::kFail;
  const json again = json::parse(gitlab_code_quality(later));
  EXPECT_EQ(again[0]["fingerprint"], report[0]["fingerprint"]);
  EXPECT_NE(again[1]["fingerprint"], report[1]["fingerprint"]);
  EXPECT_EQ(gitlab_code_quality({rows()[0]}), "[]\n");
}

TEST(CiAnnotations, RowsOfAnImageReport) {
  DiffReport report;
  ImageDiff missing;
  missing.name = "gone.png";
  missing.a = "golden/gone.png";
  missing.status = DiffStatus::kFail;
  missing.reason = "missing in B, only in A";
  ImageDiff flip;
  flip.name = "f.png";
  flip.a = "golden/f.png";
  flip.b = "out/f.png";
  flip.compared = true;
  flip.metric = DiffMetric::kFlip;
  flip.mean_error = 0.25;
  flip.max_error = 0.5;
  report.pairs = {missing, flip};
  const std::vector<CiRow> r = ci_rows(report);
  ASSERT_EQ(r.size(), 2u);
  EXPECT_EQ(r[0].file, "golden/gone.png");  // B is missing: the annotation goes on A
  EXPECT_EQ(r[0].figures, "");
  EXPECT_EQ(r[1].file, "out/f.png");
  EXPECT_EQ(r[1].figures, "FLIP mean 0.25, max 0.5");
}

}  // namespace
}  // namespace dqskin
