// `dqskin diff --annotations`: a diff's verdicts in the CI's own interface, beside its reports
// (diff_report.hpp, geometry_report.hpp). GitHub Actions reads workflow commands from a step's output
// ("::error file=…,title=…::message", docs.github.com "Workflow commands for GitHub Actions", escaped as
// actions/toolkit's command.ts escapes them) and Markdown from the file $GITHUB_STEP_SUMMARY names; GitLab
// reads a Code Quality report (docs.gitlab.com "Code Quality", the report format: a JSON array of issues
// with description, check_name, fingerprint, severity and location.path, location.lines.begin).
#pragma once

#include "dqskin/geometry_diff.hpp"
#include "dqskin/image_diff.hpp"

#include <string>
#include <vector>

namespace dqskin {

// One verdict as a CI shows it: an image pair, a clip or a file of a bake.
struct CiRow {
  DiffStatus status = DiffStatus::kPass;
  std::string name;     // the pair's name, or "clip Walk"
  std::string file;     // the file the verdict is about: the candidate (B), or A when B is missing
  std::string figures;  // the headline figures ("max 0.5  mean 0.01"); empty when nothing was measured
  std::string reason;   // why it failed or warned; empty on PASS
};

// The rows of an image diff, in its order, and of a glTF or bake diff (its failing animation findings
// first, then its clips or files).
std::vector<CiRow> ci_rows(const DiffReport& report);
std::vector<CiRow> ci_rows(const GeometryDiffReport& report);

// One workflow command per failing ("::error") or warning ("::warning") row, with the file and a title
// naming the row; passing rows give none.
std::string github_annotations(const std::vector<CiRow>& rows);

// A Markdown step summary: a heading with the verdict and counts, then a table of every row, failures
// first, then warnings, then passes, each group in the report's order.
std::string github_step_summary(const std::string& title, DiffStatus status, const std::vector<CiRow>& rows);

// A GitLab Code Quality report: one issue per failing (severity "major") or warning ("minor") row, its
// fingerprint a hash of the check, the row's name and its verdict, so that the same problem keeps its
// fingerprint from one pipeline to the next whatever its figures.
std::string gitlab_code_quality(const std::vector<CiRow>& rows);

}  // namespace dqskin
