// `dqskin diff`'s reports of a DiffReport: text for people, JSON for scripts, JUnit XML for CI
// (include/dqskin/diff_report.hpp). Formatting only: nothing here reads an image.
#include "dqskin/diff_report.hpp"
#include "diff_numbers.hpp"
#include "../base/xml_escape.hpp"

#include "dqskin/error.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace dqskin {
namespace {

using Json = nlohmann::ordered_json;  // keys in the order written
using diff_detail::number;
using diff_detail::percent;
using io::xml;

Json finite_or_null(double value) { return std::isfinite(value) ? Json(value) : Json(nullptr); }

// The thresholds as the document and a preset rule's pairs report them (infinite: null, that is off).
Json thresholds_json(const DiffThresholds& t) {
  return {{"fail", finite_or_null(t.fail)},           {"fail_percent", t.fail_percent},
          {"hard_fail", finite_or_null(t.hard_fail)}, {"warn", finite_or_null(t.warn)},
          {"warn_percent", t.warn_percent},           {"hard_warn", finite_or_null(t.hard_warn)},
          {"fail_mean", finite_or_null(t.fail_mean)}, {"warn_mean", finite_or_null(t.warn_mean)}};
}

std::string max_text(const ImageDiff& d) {
  std::string text = number(d.max_error);
  if (d.max_error != 0)
    text += " at (" + std::to_string(d.max_x) + ", " + std::to_string(d.max_y) +
            (d.max_channel.empty() ? "" : ", " + d.max_channel) + ")";
  return text;
}

bool is_flip(const ImageDiff& d) { return d.metric == DiffMetric::kFlip; }

// HDR-FLIP's exposures, after its figures.
std::string hdr_text(const ImageDiff& d) {
  if (!d.hdr_exposures) return "";
  return "  exposures " + std::to_string(d.hdr_exposures) + " from " + number(d.hdr_start) + " to " + number(d.hdr_stop);
}

// FLIP's pooled figures after its mean: the weighted quartiles.
std::string quartiles_text(const ImageDiff& d, const char* separator) {
  return "weighted quartiles " + number(d.flip_q1) + separator + number(d.flip_median) + separator + number(d.flip_q3);
}

// The metrics of a compared pair, one per line, for JUnit's failure text.
std::string metrics_lines(const ImageDiff& d) {
  std::string text = "A: " + (d.a.empty() ? "(missing)" : d.a) + "\nB: " + (d.b.empty() ? "(missing)" : d.b) + "\n";
  if (!d.compared) return text + d.problem + "\n";
  if (is_flip(d))
    text += std::string(d.hdr_exposures ? "HDR-" : "") + "FLIP mean: " + number(d.mean_error) + "\nFLIP " +
            quartiles_text(d, ", ") + "\nFLIP max: " + max_text(d) + hdr_text(d) +
            "\npixels over --warn: " + std::to_string(d.over_warn) +
            " (" + percent(d.over_warn, d.pixels) + ")\npixels over --fail: " + std::to_string(d.over_fail) + " (" +
            percent(d.over_fail, d.pixels) + ")\npixels: " + std::to_string(d.pixels) + "\n";
  else
  text += "max error: " + max_text(d) + "\nmean error: " + number(d.mean_error) + "\nRMS error: " +
          number(d.rms_error) + "\nPSNR: " + number(d.psnr) + " dB\npixels over --warn: " + std::to_string(d.over_warn) +
          " (" + percent(d.over_warn, d.pixels) + ")\npixels over --fail: " + std::to_string(d.over_fail) + " (" +
          percent(d.over_fail, d.pixels) + ")\npixels: " + std::to_string(d.pixels) + "\n";
  if (!d.heat_map.empty()) text += "heat map: " + d.heat_map + "\n";
  return text;
}

std::string summary_counts(const DiffReport& r) {
  const size_t n = r.pairs.size();
  return std::to_string(n) + (n == 1 ? " pair: " : " pairs: ") + std::to_string(r.count(DiffStatus::kPass)) + " pass, " +
         std::to_string(r.count(DiffStatus::kWarn)) + " warn, " + std::to_string(r.count(DiffStatus::kFail)) + " fail";
}

}  // namespace

std::string diff_text(const DiffReport& report) {
  std::string text;
  for (const ImageDiff& d : report.pairs) {
    text += std::string(status_name(d.status)) + "  " + printable(d.name) + "  ";
    if (!d.compared) {
      text += printable(d.problem) + "\n";
      continue;
    }
    if (is_flip(d))
      text += std::string(d.hdr_exposures ? "HDR-" : "") + "FLIP mean " + number(d.mean_error) + "  " +
              quartiles_text(d, " ") + "  max " + max_text(d) + hdr_text(d);
    else
      text += "max " + max_text(d) + "  mean " + number(d.mean_error) + "  RMS " + number(d.rms_error) + "  PSNR " +
              number(d.psnr) + " dB";
    text += "  over warn " + std::to_string(d.over_warn) + " (" + percent(d.over_warn, d.pixels) + ")  over fail " +
            std::to_string(d.over_fail) + " (" + percent(d.over_fail, d.pixels) + ")";
    if (d.masked > 0) text += "  masked " + std::to_string(d.masked);
    if (!d.rule.empty()) text += "  rule " + printable(d.rule);
    if (!d.heat_map.empty()) text += "  heat map " + printable(d.heat_map);
    text += "\n";
  }
  text += "summary: " + std::string(status_name(report.status())) + " (" + summary_counts(report) + ")\n";
  if (report.approval) {
    const bool dry = report.approval_dry_run;
    for (const Approval& a : report.approved)
      text += std::string("approved: ") + (dry ? "would " : "") +
              (a.added ? (dry ? "add " : "added ") : (dry ? "replace " : "replaced ")) + printable(a.golden) +
              (a.added ? " from " : " with ") + printable(a.candidate) + "\n";
    const size_t n = report.approved.size();
    text += std::string("approved: ") + std::to_string(n) + (n == 1 ? " golden" : " goldens") +
            (dry ? " would be replaced or added (dry run: nothing changed)" : " replaced or added") + "; then " +
            status_name(report.status_after_approval()) + "\n";
  }
  return text;
}

std::string diff_json(const DiffReport& report) {
  const DiffThresholds& t = report.thresholds;
  Json pairs = Json::array();
  for (const ImageDiff& d : report.pairs) {
    Json p;
    p["name"] = d.name;
    p["a"] = d.a.empty() ? Json(nullptr) : Json(d.a);
    p["b"] = d.b.empty() ? Json(nullptr) : Json(d.b);
    p["status"] = status_name(d.status);
    if (!d.rule.empty()) {
      // The rule's metric and thresholds, which are not the document's.
      p["rule"] = {{"match", d.rule}, {"metric", metric_name(d.metric)}, {"thresholds", thresholds_json(d.thresholds)}};
    }
    if (!d.compared) {
      p["problem"] = d.problem;
    } else {
      p["reason"] = d.reason.empty() ? Json(nullptr) : Json(d.reason);
      p["max_error"] = finite_or_null(d.max_error);
      p["max_at"] = {{"x", d.max_x}, {"y", d.max_y}};
      if (!is_flip(d)) p["max_at"]["channel"] = d.max_channel;
      p["mean_error"] = finite_or_null(d.mean_error);
      if (is_flip(d)) p["weighted_quartiles"] = {d.flip_q1, d.flip_median, d.flip_q3};
      if (d.hdr_exposures) p["hdr_exposures"] = {{"count", d.hdr_exposures}, {"start", d.hdr_start}, {"stop", d.hdr_stop}};
      p["rms_error"] = finite_or_null(d.rms_error);
      p["psnr"] = finite_or_null(d.psnr);
      p["pixels"] = d.pixels;
      p["pixels_over_warn"] = d.over_warn;
      p["pixels_over_fail"] = d.over_fail;
      p["heat_map"] = d.heat_map.empty() ? Json(nullptr) : Json(d.heat_map);
      if (d.masked > 0) p["pixels_masked"] = d.masked;
    }
    pairs.push_back(std::move(p));
  }
  Json doc;
  doc["a"] = report.a;
  doc["b"] = report.b;
  doc["metric"] = metric_name(report.metric);
  if (report.metric == DiffMetric::kFlip) doc["pixels_per_degree"] = report.pixels_per_degree;
  doc["thresholds"] = thresholds_json(t);
  doc["pairs"] = std::move(pairs);
  if (report.approval) {
    Json files = Json::array();
    for (const Approval& a : report.approved)
      files.push_back({{"name", a.name}, {"golden", a.golden}, {"candidate", a.candidate}, {"added", a.added}});
    doc["approval"] = {{"dry_run", report.approval_dry_run}, {"files", std::move(files)},
                       {"status_after", status_name(report.status_after_approval())}};
  }
  doc["summary"] = {{"status", status_name(report.status())},
                    {"pairs", report.pairs.size()},
                    {"pass", report.count(DiffStatus::kPass)},
                    {"warn", report.count(DiffStatus::kWarn)},
                    {"fail", report.count(DiffStatus::kFail)}};
  // File names come from the file system: invalid UTF-8 is replaced rather than refused.
  return doc.dump(2, ' ', false, Json::error_handler_t::replace) + "\n";
}

std::string diff_junit(const DiffReport& report) {
  const DiffThresholds& t = report.thresholds;
  const std::string tests = std::to_string(report.pairs.size());
  const std::string failures = std::to_string(report.count(DiffStatus::kFail));
  std::string x = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  x += "<testsuites name=\"dqskin diff\" tests=\"" + tests + "\" failures=\"" + failures + "\" errors=\"0\">\n";
  x += "  <testsuite name=\"" + xml("dqskin diff " + report.a + " " + report.b, true) + "\" tests=\"" + tests +
       "\" failures=\"" + failures + "\" errors=\"0\" skipped=\"0\">\n";
  x += "    <properties>\n";
  std::vector<std::pair<const char*, std::string>> properties = {
      {"a", report.a},
      {"b", report.b},
      {"metric", metric_name(report.metric)},
      {"fail", number(t.fail)},
      {"failpercent", number(t.fail_percent)},
      {"hardfail", number(t.hard_fail)},
      {"warn", number(t.warn)},
      {"warnpercent", number(t.warn_percent)},
      {"hardwarn", number(t.hard_warn)},
      {"failmean", number(t.fail_mean)},
      {"warnmean", number(t.warn_mean)}};
  if (report.metric == DiffMetric::kFlip) properties.emplace_back("pixels_per_degree", number(report.pixels_per_degree));
  for (const auto& [name, value] : properties)
    x += "      <property name=\"" + std::string(name) + "\" value=\"" + xml(value, true) + "\"/>\n";
  x += "    </properties>\n";
  for (const ImageDiff& d : report.pairs) {
    x += "    <testcase classname=\"dqskin.diff\" name=\"" + xml(d.name, true) + "\"";
    if (d.status == DiffStatus::kPass) {
      x += "/>\n";
      continue;
    }
    x += ">\n";
    if (d.status == DiffStatus::kFail)
      x += "      <failure type=\"FAIL\" message=\"" + xml(d.reason, true) + "\">" + xml(metrics_lines(d), false) +
           "</failure>\n";
    else
      x += "      <system-out>" + xml("WARN: " + d.reason + "\n" + metrics_lines(d), false) + "</system-out>\n";
    x += "    </testcase>\n";
  }
  x += "  </testsuite>\n</testsuites>\n";
  return x;
}

}  // namespace dqskin
