#include "dqskin/ci_annotations.hpp"
#include "diff_numbers.hpp"
#include "../base/sha256.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>

namespace dqskin {
namespace {

using diff_detail::number;
using Json = nlohmann::ordered_json;

// actions/toolkit command.ts: a message escapes '%', CR and LF; a property also ':' and ','.
std::string escape_data(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (c == '%') out += "%25";
    else if (c == '\r') out += "%0D";
    else if (c == '\n') out += "%0A";
    else out += c;
  }
  return out;
}

std::string escape_property(const std::string& text) {
  std::string out;
  for (char c : escape_data(text)) {
    if (c == ':') out += "%3A";
    else if (c == ',') out += "%2C";
    else out += c;
  }
  return out;
}

// Markdown table cells: a '|' would end the cell, a line break the row; '\\', '`', emphasis, link and
// math characters are escaped so that a file name shows as it is and never becomes a link.
std::string cell(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (c == '|' || c == '\\' || c == '`' || c == '*' || c == '_' || c == '<' || c == '[' || c == ']' || c == '!' ||
        c == '~' || c == '$')
      out += '\\';
    out += c == '\n' || c == '\r' ? ' ' : c;
  }
  return out;
}

std::string image_figures(const ImageDiff& d) {
  if (!d.compared) return "";
  if (d.metric == DiffMetric::kFlip) return "FLIP mean " + number(d.mean_error) + ", max " + number(d.max_error);
  return "max " + number(d.max_error) + ", mean " + number(d.mean_error);
}

}  // namespace

std::vector<CiRow> ci_rows(const DiffReport& report) {
  std::vector<CiRow> rows;
  for (const ImageDiff& d : report.pairs)
    rows.push_back({d.status, d.name, d.b.empty() ? d.a : d.b, image_figures(d), d.reason});
  return rows;
}

std::vector<CiRow> ci_rows(const GeometryDiffReport& report) {
  std::vector<CiRow> rows;
  for (const AnimationFinding& f : report.findings)
    if (f.severity != DiffStatus::kPass) rows.push_back({f.severity, "clip " + f.clip, report.b, "", f.text});
  for (const ClipGeometryDiff& c : report.clips) {
    const std::string unit = report.relative ? " of the diagonal" : " m";  // glTF's unit
    const double scale = report.relative && c.diagonal > 0 ? 1 / c.diagonal : 1;
    rows.push_back({c.status, report.bake ? c.name : "clip " + c.name, report.bake ? report.b + "/" + c.name : report.b,
                    "max " + number(c.max_error * scale) + unit + ", mean " + number(c.mean_error * scale) + unit,
                    c.reason});
  }
  return rows;
}

std::string github_annotations(const std::vector<CiRow>& rows) {
  std::string out;
  for (const CiRow& r : rows) {
    if (r.status == DiffStatus::kPass) continue;
    out += r.status == DiffStatus::kFail ? "::error" : "::warning";
    out += " file=" + escape_property(r.file) + ",title=" + escape_property("dqskin diff: " + r.name) +
           "::" + escape_data(r.reason + (r.figures.empty() ? "" : " (" + r.figures + ")")) + "\n";
  }
  return out;
}

std::string github_step_summary(const std::string& title, DiffStatus status, const std::vector<CiRow>& rows) {
  const auto count = [&rows](DiffStatus s) {
    return std::to_string(std::count_if(rows.begin(), rows.end(), [s](const CiRow& r) { return r.status == s; }));
  };
  std::string md = "### " + cell(title) + ": " + status_name(status) + "\n\n" + count(DiffStatus::kPass) + " pass, " +
                   count(DiffStatus::kWarn) + " warn, " + count(DiffStatus::kFail) + " fail\n\n";
  md += "| | name | figures | reason |\n|---|---|---|---|\n";
  for (DiffStatus s : {DiffStatus::kFail, DiffStatus::kWarn, DiffStatus::kPass})
    for (const CiRow& r : rows)
      if (r.status == s) md += std::string("| ") + status_name(s) + " | " + cell(r.name) + " | " + cell(r.figures) + " | " + cell(r.reason) + " |\n";
  return md + "\n";
}

std::string gitlab_code_quality(const std::vector<CiRow>& rows) {
  Json issues = Json::array();
  for (const CiRow& r : rows) {
    if (r.status == DiffStatus::kPass) continue;
    const std::string verdict = status_name(r.status);
    const std::string key = "dqskin-diff\n" + r.name + "\n" + verdict;
    Json issue;
    issue["type"] = "issue";
    issue["check_name"] = "dqskin-diff";
    issue["description"] = "dqskin diff " + r.name + ": " + verdict + ", " + r.reason +
                           (r.figures.empty() ? "" : " (" + r.figures + ")");
    issue["categories"] = {"Bug Risk"};
    issue["severity"] = r.status == DiffStatus::kFail ? "major" : "minor";
    issue["fingerprint"] = sha256_hex(std::span<const char>(key.data(), key.size())).substr(0, 32);
    issue["location"] = {{"path", r.file}, {"lines", {{"begin", 1}}}};
    issues.push_back(std::move(issue));
  }
  return issues.dump(2, ' ', false, Json::error_handler_t::replace) + "\n";
}

}  // namespace dqskin
