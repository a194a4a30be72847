#include "dqskin/diff_page.hpp"
#include "diff_numbers.hpp"
#include "page_parts.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace dqskin {
namespace {

using diff_detail::attribute;
using diff_detail::number;
using diff_detail::percent;
using diff_detail::status_class;
using diff_detail::text;

// The order of the page: failures, then warnings, then passes; within each, pairs that could not be
// compared first, then by their headline error (FLIP's mean, idiff's max), largest first; then by name.
std::vector<size_t> page_order(const DiffReport& r) {
  std::vector<size_t> order(r.pairs.size());
  std::iota(order.begin(), order.end(), size_t(0));
  const auto headline = [](const ImageDiff& d) {
    const double e = d.metric == DiffMetric::kFlip ? d.mean_error : d.max_error;
    return std::isnan(e) ? std::numeric_limits<double>::infinity() : e;  // a NaN sorts as the worst, not at random
  };
  std::stable_sort(order.begin(), order.end(), [&](size_t i, size_t j) {
    const ImageDiff &a = r.pairs[i], &b = r.pairs[j];
    if (a.status != b.status) return a.status > b.status;
    if (a.compared != b.compared) return !a.compared;
    return headline(a) > headline(b);
  });
  return order;
}

std::string thresholds_text(const ImageDiff& d) {
  const DiffThresholds& t = d.thresholds;
  std::string s;
  const auto add = [&s](const char* name, double v, bool on) {
    if (on) s += (s.empty() ? "" : ", ") + std::string(name) + " " + number(v);
  };
  add("--fail", t.fail, std::isfinite(t.fail));
  add("--failpercent", t.fail_percent, std::isfinite(t.fail) && t.fail_percent > 0);
  add("--hardfail", t.hard_fail, std::isfinite(t.hard_fail));
  add("--failmean", t.fail_mean, std::isfinite(t.fail_mean));
  add("--warn", t.warn, std::isfinite(t.warn));
  add("--warnpercent", t.warn_percent, std::isfinite(t.warn) && t.warn_percent > 0);
  add("--hardwarn", t.hard_warn, std::isfinite(t.hard_warn));
  add("--warnmean", t.warn_mean, std::isfinite(t.warn_mean));
  return s.empty() ? "none" : s;
}

std::string figures_rows(const ImageDiff& d) {
  std::string s;
  const auto row = [&s](const std::string& name, const std::string& value) {
    s += "<tr><th>" + text(name) + "</th><td>" + text(value) + "</td></tr>";
  };
  if (!d.compared) {
    row("problem", d.problem);
  } else if (d.metric == DiffMetric::kFlip) {
    row("FLIP mean", number(d.mean_error));
    row("weighted quartiles", number(d.flip_q1) + ", " + number(d.flip_median) + ", " + number(d.flip_q3));
    row("FLIP max", number(d.max_error) + (d.max_error > 0 ? " at (" + std::to_string(d.max_x) + ", " + std::to_string(d.max_y) + ")" : ""));
  } else {
    row("max error", number(d.max_error) + (d.max_error > 0 ? " at (" + std::to_string(d.max_x) + ", " + std::to_string(d.max_y) + ", " + d.max_channel + ")" : ""));
    row("mean error", number(d.mean_error));
    row("RMS error", number(d.rms_error));
    row("PSNR", number(d.psnr) + " dB");
  }
  if (d.compared) {
    row("pixels over --warn", std::to_string(d.over_warn) + " (" + percent(d.over_warn, d.pixels) + ")");
    row("pixels over --fail", std::to_string(d.over_fail) + " (" + percent(d.over_fail, d.pixels) + ")");
    row("pixels compared", std::to_string(d.pixels) + (d.masked ? " (" + std::to_string(d.masked) + " masked)" : ""));
  }
  row("metric", metric_name(d.metric));
  row("thresholds", thresholds_text(d) + (d.rule.empty() ? "" : " (rule " + d.rule + ")"));
  row("A", d.a.empty() ? "(missing)" : d.a);
  row("B", d.b.empty() ? "(missing)" : d.b);
  return s;
}

// The colour bar of an idiff heat map (the map itself has none): black up to --fail, then viridis (its
// sRGB colours at 0, ¼, ½, ¾ and 1) to the pair's max.
std::string idiff_legend(const ImageDiff& d) {
  return "<div class=\"legend\"><span>" + text("\u2264 " + number(d.thresholds.fail)) +
         "</span><span class=\"bar\"></span><span>" + text(number(d.max_error)) + "</span></div>"
         "<p class=\"note\">largest channel difference; black at most --fail</p>";
}

}  // namespace

std::string diff_page_html(const DiffReport& r) {
  const std::vector<size_t> order = page_order(r);
  const std::string title = "dqskin diff " + r.a + " " + r.b;
  std::string h = "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>" + text(title) +
                  "</title><meta name=\"viewport\" content=\"width=device-width\"><style>" + diff_detail::kStyle + "</style></head><body>\n";
  const DiffStatus overall = r.status();
  h += "<header id=\"index\" class=\"" + status_class(overall) + "\"><h1><span class=\"status\">" + status_name(overall) +
       "</span> " + text(title) + "</h1><p>" + std::to_string(r.pairs.size()) + " pairs: " +
       std::to_string(r.count(DiffStatus::kFail)) + " fail, " + std::to_string(r.count(DiffStatus::kWarn)) + " warn, " +
       std::to_string(r.count(DiffStatus::kPass)) + " pass. Metric " + metric_name(r.metric) +
       (r.metric == DiffMetric::kFlip ? " at " + number(r.pixels_per_degree) + " pixels per degree" : std::string()) +
       ". Failing first, then by error.</p>\n<table><tr><th></th><th>pair</th><th>error</th><th>reason</th></tr>\n";
  for (size_t k = 0; k < order.size(); ++k) {
    const ImageDiff& d = r.pairs[order[k]];
    const std::string error = !d.compared ? "\u2013"
                              : d.metric == DiffMetric::kFlip ? "FLIP mean " + number(d.mean_error)
                                                              : "max " + number(d.max_error);
    h += "<tr class=\"" + status_class(d.status) + "\"><td><span class=\"status\">" + status_name(d.status) +
         "</span></td><td><a href=\"#p" + std::to_string(k) + "\">" + text(d.name) + "</a></td><td>" + text(error) +
         "</td><td>" + text(d.reason) + "</td></tr>\n";
  }
  h += "</table></header>\n";
  for (size_t k = 0; k < order.size(); ++k) {
    const ImageDiff& d = r.pairs[order[k]];
    h += "<section id=\"p" + std::to_string(k) + "\" class=\"pair " + status_class(d.status) + "\" data-name=\"" +
         attribute(d.name) + "\" data-status=\"" + status_name(d.status) + "\"><h2><span class=\"status\">" +
         status_name(d.status) + "</span> " + text(d.name) + "</h2>";
    if (!d.reason.empty()) h += "<p>" + text(d.reason) + "</p>";
    h += "<table class=\"figures\">" + figures_rows(d) + "</table>";
    if (!d.page_a.empty() || !d.page_b.empty()) {
      h += "<div class=\"views\">";
      if (!d.page_a.empty())
        h += "<figure><figcaption>A (reference)</figcaption><img class=\"a\" loading=\"lazy\" src=\"" + attribute(d.page_a) + "\" alt=\"A\"></figure>";
      if (!d.page_b.empty())
        h += "<figure><figcaption>B (candidate)</figcaption><img class=\"b\" loading=\"lazy\" src=\"" + attribute(d.page_b) + "\" alt=\"B\"></figure>";
      if (!d.page_difference.empty()) {
        h += "<figure><figcaption>difference</figcaption><img class=\"difference\" loading=\"lazy\" src=\"" +
             attribute(d.page_difference) + "\" alt=\"difference\">";
        h += d.metric == DiffMetric::kFlip ? "<p class=\"note\">FLIP per pixel, its colour bar beside the map</p>" : idiff_legend(d);
        h += "</figure>";
      }
      h += "</div>";
      if (!d.page_a.empty() && !d.page_b.empty() && d.compared)
        h += diff_detail::compare_box(d.page_a, d.page_b);
    }
    h += diff_detail::section_nav(k, order.size()) + "</section>\n";
  }
  h += "<script>" + std::string(diff_detail::kScript) + "</script>\n</body></html>\n";
  return h;
}

}  // namespace dqskin
