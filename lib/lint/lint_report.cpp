// The reports of `dqskin lint`, in the conventions of `dqskin diff`'s (diff_report.hpp): text for people,
// one JSON document for scripts, JUnit XML for CI. Nothing of the run (times, hosts) goes in, so the same
// results give the same bytes.
#include "dqskin/lint.hpp"

#include "../base/xml_escape.hpp"
#include "dqskin/error.hpp"
#include "lint_checks.hpp"

#include <nlohmann/json.hpp>

#include <map>

namespace dqskin {
namespace {

using io::xml;
using json = nlohmann::ordered_json;  // keys in the order written, as diff's reports

// "clean" when there is nothing to say, else the worst severity.
std::string status_of(const LintFileResult& r) {
  if (!r.error.empty()) return "error";
  if (r.findings.empty()) return "clean";
  return to_string(r.worst());
}

std::string overall(const std::vector<LintFileResult>& results) {
  std::string worst = "clean";
  for (const char* level : {"info", "warning", "error"})
    for (const LintFileResult& r : results)
      if (status_of(r) == level) worst = level;
  return worst;
}

json nullable(long long v) { return v < 0 ? json(nullptr) : json(v); }

}  // namespace

std::string lint_text(const std::vector<LintFileResult>& results) {
  std::string t;
  size_t counts[4] = {0, 0, 0, 0};  // clean, info, warning, error
  for (const LintFileResult& r : results) {
    const std::string status = status_of(r);
    counts[status == "clean" ? 0 : status == "info" ? 1 : status == "warning" ? 2 : 3]++;
    t += printable(r.path) + ": ";
    if (!r.error.empty()) {
      t += "error: " + printable(r.error) + "\n";  // loader messages quote the file's own strings
      continue;
    }
    t += status + "\n";
    for (const LintFinding& f : r.findings) {
      std::string severity = to_string(f.severity);
      severity.resize(8, ' ');
      t += "  " + severity + f.check + " (" + std::to_string(f.count) + "): " + f.message + "\n";
    }
  }
  t += "summary: " + overall(results) + " (" + std::to_string(results.size()) + " files: " + std::to_string(counts[0]) +
       " clean, " + std::to_string(counts[1]) + " info, " + std::to_string(counts[2]) + " warning, " +
       std::to_string(counts[3]) + " error)\n";
  return t;
}

std::string lint_json(const std::vector<LintFileResult>& results, const LintOptions& options) {
  json files = json::array();
  std::map<std::string, size_t> counts;  // by status
  for (const LintFileResult& r : results) {
    const std::string status = status_of(r);
    ++counts[status];
    json file = {{"file", r.path}, {"status", status}};
    if (!r.error.empty()) {
      file["problem"] = r.error;
    } else {
      json findings = json::array();
      for (const LintFinding& f : r.findings)
        findings.push_back({{"check", f.check},
                            {"severity", to_string(f.severity)},
                            {"count", f.count},
                            {"message", f.message},
                            {"worst",
                             {{"where", f.worst.where},
                              {"vertex", nullable(f.worst.vertex)},
                              {"joint", nullable(f.worst.joint)},
                              {"key", nullable(f.worst.key)},
                              {"value", f.worst.value}}}});
      file["findings"] = std::move(findings);
    }
    files.push_back(std::move(file));
  }
  json summary = {{"status", overall(results)}, {"files", results.size()}};
  for (const char* status : {"clean", "info", "warning", "error"}) summary[status] = counts[status];
  const json doc = {{"files", std::move(files)},
                    {"options",
                     {{"sum_tolerance", options.sum_tolerance},
                      {"max_influences", options.max_influences},
                      {"bind_tolerance", options.bind_tolerance},
                      {"scale_tolerance", options.scale_tolerance},
                      {"unit_tolerance", options.unit_tolerance}}},
                    {"summary", std::move(summary)}};
  return doc.dump(2, ' ', false, json::error_handler_t::replace) + "\n";
}

std::string lint_junit(const std::vector<LintFileResult>& results) {
  std::string cases;
  size_t tests = 0, failures = 0;
  auto testcase = [&](const std::string& name, const std::string& inner) {
    ++tests;
    cases += "    <testcase classname=\"dqskin.lint\" name=\"" + xml(name, true) + "\"";
    cases += inner.empty() ? "/>\n" : ">\n" + inner + "    </testcase>\n";
  };
  for (const LintFileResult& r : results) {
    if (!r.error.empty()) {
      ++failures;
      testcase(r.path + " read", "      <failure type=\"error\" message=\"" + xml(r.error, true) + "\"/>\n");
      continue;
    }
    for (const LintCheckInfo& check : lint_checks()) {
      std::string inner;
      for (const LintFinding& f : r.findings) {
        if (f.check != check.id) continue;
        const std::string line =
            std::string(to_string(f.severity)) + ": " + std::to_string(f.count) + " cases; worst: " + f.message;
        if (f.severity == LintSeverity::kError) {
          ++failures;
          inner = "      <failure type=\"error\" message=\"" + xml(f.message, true) + "\">" + xml(line, false) +
                  "</failure>\n";
        } else {
          inner = "      <system-out>" + xml(line, false) + "</system-out>\n";
        }
      }
      testcase(r.path + " " + check.id, inner);
    }
  }
  std::string x = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  x += "<testsuites name=\"dqskin lint\" tests=\"" + std::to_string(tests) + "\" failures=\"" +
       std::to_string(failures) + "\" errors=\"0\">\n";
  x += "  <testsuite name=\"dqskin lint\" tests=\"" + std::to_string(tests) + "\" failures=\"" +
       std::to_string(failures) + "\" errors=\"0\" skipped=\"0\">\n";
  x += cases;
  x += "  </testsuite>\n</testsuites>\n";
  return x;
}

}  // namespace dqskin
