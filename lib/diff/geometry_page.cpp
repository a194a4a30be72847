// The page of a geometric `dqskin diff --html` (dqskin/diff_page.hpp): the image page's look and
// interactions (page_parts.hpp) over clips instead of image pairs, with what only geometry has: both
// surfaces at the worst frame shaded by their distance to each other, the error over the clip's frames
// as a chart, and the joints that carry it.
#include "dqskin/diff_page.hpp"
#include "dqskin/geometry_report.hpp"
#include "diff_numbers.hpp"
#include "page_parts.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numeric>

namespace dqskin {
namespace {

using diff_detail::attribute;
using diff_detail::number;
using diff_detail::percent;
using diff_detail::scene_length;
using diff_detail::status_class;
using diff_detail::text;

double relative(double value, double diagonal) { return diagonal > 0 ? value / diagonal : 0; }

// A clip's threshold in scene units: relative thresholds are fractions of its diagonal.
double absolute(const GeometryDiffReport& r, const ClipGeometryDiff& c, double threshold) {
  return r.relative ? threshold * c.diagonal : threshold;
}

// Failures, then warnings, then passes; within each by the error relative to the clip's size (so that a
// large character's millimetres do not hide a small prop's), largest first, then in the report's order.
std::vector<size_t> page_order(const GeometryDiffReport& r) {
  std::vector<size_t> order(r.clips.size());
  std::iota(order.begin(), order.end(), size_t(0));
  const auto headline = [](const ClipGeometryDiff& c) {
    const double e = relative(c.max_error, c.diagonal);
    return std::isnan(e) || c.frames.empty() ? std::numeric_limits<double>::infinity() : e;
  };
  std::stable_sort(order.begin(), order.end(), [&](size_t i, size_t j) {
    const ClipGeometryDiff &a = r.clips[i], &b = r.clips[j];
    if (a.status != b.status) return a.status > b.status;
    return headline(a) > headline(b);
  });
  return order;
}

std::string max_text(const ClipGeometryDiff& c) {
  if (c.frames.empty()) return "\u2013";
  return scene_length(c.max_error) + " (" + number(relative(c.max_error, c.diagonal)) + " of the diagonal)";
}

// The thresholds that judge a clip, as given and, when relative, in scene units for this clip.
std::string thresholds_text(const GeometryDiffReport& r, const ClipGeometryDiff& c) {
  const DiffThresholds& t = r.thresholds;
  std::string s;
  const auto add = [&](const char* name, double v, bool length) {
    s += (s.empty() ? "" : ", ") + std::string(name) + " " + number(v);
    if (length && r.relative) s += " (" + scene_length(absolute(r, c, v)) + ")";
  };
  add("--fail", t.fail, true);
  if (t.fail_percent > 0) add("--failpercent", t.fail_percent, false);
  if (std::isfinite(t.hard_fail)) add("--hardfail", t.hard_fail, true);
  add("--warn", t.warn, true);
  if (t.warn_percent > 0) add("--warnpercent", t.warn_percent, false);
  if (std::isfinite(t.hard_warn)) add("--hardwarn", t.hard_warn, true);
  return s + (r.relative ? " of the diagonal" : " scene units");
}

std::string figures_rows(const GeometryDiffReport& r, const ClipGeometryDiff& c) {
  std::string s;
  const auto row = [&s](const std::string& name, const std::string& value) {
    s += "<tr><th>" + text(name) + "</th><td>" + text(value) + "</td></tr>";
  };
  if (!c.frames.empty()) {
    row("max error", max_text(c));
    if (r.bake) {
      row("at", std::string(c.name.ends_with(".exr") ? "texel " : "vertex ") + std::to_string(c.worst.vertex));
    } else {
      row("at", "t = " + number(c.worst.time) + " s, " + (c.worst.side == 'A' ? "A's" : "B's") + " vertex " +
                    std::to_string(c.worst.vertex) + ", joint " + c.worst.joint);
      row("A to B, B to A", scene_length(c.max_a_to_b) + ", " + scene_length(c.max_b_to_a));
    }
    row(r.bake ? "p99" : "p99 (worst frame)", scene_length(c.p99_error));
    row("mean", scene_length(c.mean_error));
    const bool texture = r.bake && c.name.ends_with(".exr");
    if (!texture) row("normals", number(c.max_normal_degrees) + " deg at most");
    row("diagonal", scene_length(c.diagonal));
    if (!r.bake)
      row("frames", std::to_string(c.frames.size()) + ", t = " + number(c.frames.front().time) + " to " +
                        number(c.frames.back().time) + " s");
    row("samples over --warn", std::to_string(c.over_warn) + " (" + percent(c.over_warn, c.samples) + ")");
    row("samples over --fail", std::to_string(c.over_fail) + " (" + percent(c.over_fail, c.samples) + ") of " +
                                   std::to_string(c.samples));
  }
  row("thresholds", thresholds_text(r, c));
  if (!r.bake && c.name_b != c.name) row("B's clip", c.name_b);
  return s;
}

// 1, 2 or 5 times a power of ten, the least at least `v` (> 0): the top of a chart's axis.
double nice_ceiling(double v) {
  const double power = std::pow(10.0, std::floor(std::log10(v)));
  for (const double m : {1.0, 2.0, 5.0, 10.0})
    if (m * power >= v * (1 - 1e-12)) return m * power;
  return 10 * power;
}

std::string coordinate(double v) {
  char s[32];
  std::snprintf(s, sizeof s, "%.1f", v);
  return s;
}

// The clip's error over its frames as an inline SVG: the largest, 99th-percentile and mean distance of each
// frame, the thresholds that lie within the axis as dashed lines, the worst frame marked; lengths in scene
// units on the axis. Every frame a point with its figures as a tooltip.
std::string error_chart(const GeometryDiffReport& r, const ClipGeometryDiff& c) {
  constexpr double kWidth = 640, kHeight = 210, kLeft = 70, kRight = 110, kTop = 12, kBottom = 30;
  constexpr double kPlotW = kWidth - kLeft - kRight, kPlotH = kHeight - kTop - kBottom;
  const double t0 = c.frames.front().time, t1 = c.frames.back().time;
  double peak = 0;
  for (const FrameDiff& f : c.frames)
    if (std::isfinite(f.max_error)) peak = std::max(peak, f.max_error);
  struct Line {
    std::string names;
    double value;
    const char* color;
  };
  std::vector<Line> lines;
  const auto line = [&](const char* name, double threshold, const char* color) {
    const double v = absolute(r, c, threshold);
    if (!std::isfinite(v)) return;
    for (Line& l : lines)
      if (l.value == v) return void(l.names += ", " + std::string(name));
    lines.push_back({name, v, color});
  };
  line("--fail", r.thresholds.fail, "var(--fail)");
  line("--hardfail", r.thresholds.hard_fail, "var(--fail)");
  line("--warn", r.thresholds.warn, "var(--warn)");
  line("--hardwarn", r.thresholds.hard_warn, "var(--warn)");
  // The axis fits the data; a threshold far above it is named below the chart instead of flattening it.
  double top = peak > 0 ? nice_ceiling(peak * 1.05) : 0;
  if (top == 0)
    for (const Line& l : lines)
      if (l.value > 0) top = top == 0 ? l.value : std::min(top, l.value);
  if (top == 0) top = 1;
  const auto x = [&](double t) { return kLeft + (t1 > t0 ? (t - t0) / (t1 - t0) * kPlotW : kPlotW / 2); };
  const auto y = [&](double e) { return kTop + kPlotH - std::clamp(e / top, 0.0, 1.0) * kPlotH; };

  std::string s = "<svg class=\"chart\" role=\"img\" viewBox=\"0 0 " + coordinate(kWidth) + " " + coordinate(kHeight) +
                  "\" width=\"" + coordinate(kWidth) + "\" height=\"" + coordinate(kHeight) + "\"><title>" +
                  text("error over the frames of " + c.name) + "</title>";
  s += "<rect class=\"plot\" x=\"" + coordinate(kLeft) + "\" y=\"" + coordinate(kTop) + "\" width=\"" + coordinate(kPlotW) +
       "\" height=\"" + coordinate(kPlotH) + "\"/>";
  for (const double f : {0.0, 0.5, 1.0})
    s += "<text class=\"axis\" x=\"" + coordinate(kLeft - 6) + "\" y=\"" + coordinate(y(f * top) + 4) +
         "\" text-anchor=\"end\">" + text(diff_detail::length_with_unit(f * top, top)) + "</text>";
  s += "<text class=\"axis\" x=\"" + coordinate(kLeft) + "\" y=\"" + coordinate(kHeight - 10) + "\">" +
       text("t = " + number(t0) + " s") + "</text><text class=\"axis\" x=\"" + coordinate(kLeft + kPlotW) + "\" y=\"" +
       coordinate(kHeight - 10) + "\" text-anchor=\"end\">" + text(number(t1) + " s") + "</text>";
  std::string above;
  for (const Line& l : lines) {
    if (l.value > top) {
      above += (above.empty() ? "" : ", ") + l.names + " " + scene_length(l.value);
      continue;
    }
    s += "<line class=\"threshold\" x1=\"" + coordinate(kLeft) + "\" x2=\"" + coordinate(kLeft + kPlotW) + "\" y1=\"" +
         coordinate(y(l.value)) + "\" y2=\"" + coordinate(y(l.value)) + "\" stroke=\"" + l.color + "\"/><text class=\"axis\" x=\"" +
         coordinate(kLeft + kPlotW + 6) + "\" y=\"" + coordinate(y(l.value) + 4) + "\" fill=\"" + l.color + "\">" +
         text(l.names) + "</text>";
  }
  if (!c.frames.empty())
    s += "<line class=\"worst\" x1=\"" + coordinate(x(c.worst.time)) + "\" x2=\"" + coordinate(x(c.worst.time)) + "\" y1=\"" +
         coordinate(kTop) + "\" y2=\"" + coordinate(kTop + kPlotH) + "\"><title>" + text("worst frame, t = " + number(c.worst.time) + " s") +
         "</title></line>";
  // One path per series, broken where a figure is not finite (a NaN position), so that no line crosses it.
  const auto series = [&](const char* name, double FrameDiff::*member) {
    std::string d;
    bool pen = false;
    for (const FrameDiff& f : c.frames) {
      if (!std::isfinite(f.*member)) {
        pen = false;
        continue;
      }
      d += (pen ? " L" : (d.empty() ? "M" : " M")) + coordinate(x(f.time)) + " " + coordinate(y(f.*member));
      pen = true;
    }
    if (!d.empty()) s += "<path class=\"" + std::string(name) + "\" d=\"" + d + "\"/>";
  };
  series("mean", &FrameDiff::mean_error);
  series("p99", &FrameDiff::p99_error);
  series("max", &FrameDiff::max_error);
  for (const FrameDiff& f : c.frames)
    s += "<circle class=\"frame\" cx=\"" + coordinate(x(f.time)) + "\" cy=\"" + coordinate(y(f.max_error)) + "\" r=\"2.5\"><title>" +
         text("t = " + number(f.time) + " s: max " + scene_length(f.max_error) + " at " + f.worst_joint + ", p99 " +
              scene_length(f.p99_error) + ", mean " + scene_length(f.mean_error) + ", normals " +
              number(f.max_normal_degrees) + " deg") +
         "</title></circle>";
  s += "</svg><p class=\"note\"><span class=\"key max\">max</span> <span class=\"key p99\">p99</span> <span class=\"key mean\">mean</span> "
       "distance per frame; the line marks the worst frame" +
       (above.empty() ? std::string() : text("; above the chart: " + above)) + "</p>";
  return s;
}

std::string joints_table(const ClipGeometryDiff& c) {
  constexpr size_t kShown = 8;
  std::string s = "<table class=\"joints\"><tr><th>worst joints</th><th>max</th><th>at</th></tr>";
  for (size_t j = 0; j < c.joints.size() && j < kShown; ++j)
    s += "<tr><td>" + text(c.joints[j].joint) + "</td><td>" + text(scene_length(c.joints[j].max_error)) + "</td><td>" +
         text("t = " + number(c.joints[j].time) + " s") + "</td></tr>";
  if (c.joints.size() > kShown)
    s += "<tr><td colspan=\"3\" class=\"note\">and " + std::to_string(c.joints.size() - kShown) + " more (--json lists them)</td></tr>";
  return s + "</table>";
}

std::string header_facts(const GeometryDiffReport& r) {
  std::string s = "<table class=\"facts\">";
  const auto row = [&s](const std::string& name, const std::string& value) {
    s += "<tr><th>" + text(name) + "</th><td>" + text(value) + "</td></tr>";
  };
  if (!r.bake) {
    row("A", r.a + " (" + std::to_string(r.vertices_a) + " vertices)");
    row("B", r.b + " (" + std::to_string(r.vertices_b) + " vertices)");
    row("deformed", std::string(to_string(r.mode)) + " on " + r.deformer);
    row("correspondence", r.identity ? "the same vertices in the same order at " + pose_text(r)
                                     : "closest surface points at " + pose_text(r) + "; there A to B max " +
                                           scene_length(r.rest_a_to_b) + ", B to A max " + scene_length(r.rest_b_to_a));
    row("normals", "vertex normals at " + std::to_string(r.smooth_normals_a) + " of A's and " +
                       std::to_string(r.smooth_normals_b) + " of B's vertices, face normals on " +
                       std::to_string(r.face_normals_a) + " of A's and " + std::to_string(r.face_normals_b) + " of B's triangles");
  } else {
    row("A", r.a);
    row("B", r.b);
  }
  return s + "</table>";
}

std::string findings_list(const GeometryDiffReport& r) {
  if (r.findings.empty()) return "";
  std::string s = "<h2>animations</h2><ul class=\"findings\">";
  for (const AnimationFinding& f : r.findings)
    s += "<li class=\"" + status_class(f.severity) + "\"><span class=\"status\">" +
         (f.severity == DiffStatus::kPass ? "note" : status_name(f.severity)) + "</span> clip " + text(f.clip) + ": " +
         text(f.text) + "</li>";
  return s + "</ul>";
}

// What the geometric page adds to the image page's style sheet.
constexpr const char* kGeometryStyle = R"(
.views img, .stack img { image-rendering: auto; max-width: 560px; max-height: 410px; }
svg.chart { display: block; margin-top: 10px; max-width: 100%; height: auto; font: 11px system-ui, sans-serif; }
svg.chart .plot { fill: #181818; stroke: #333; } svg.chart .axis { fill: #aaa; }
svg.chart path { fill: none; stroke-width: 1.5; } svg.chart .max { stroke: #eee; } svg.chart .p99 { stroke: #8ab4f8; }
svg.chart .mean { stroke: #777; } svg.chart .frame { fill: #eee; } svg.chart .threshold { stroke-dasharray: 5 4; }
svg.chart .worst { stroke: #e5484d; stroke-opacity: 0.6; }
.key::before { content: ""; display: inline-block; width: 14px; height: 3px; margin-right: 4px; vertical-align: middle; }
.key.max::before { background: #eee; } .key.p99::before { background: #8ab4f8; } .key.mean::before { background: #777; }
.findings { margin: 0; padding-left: 18px; } .findings li { list-style: none; margin: 2px 0; }
.findings li.pass .status { background: #555; color: #ddd; } table.joints, table.facts { margin-top: 6px; }
)";

}  // namespace

std::string geometry_page_html(const GeometryDiffReport& r) {
  const std::vector<size_t> order = page_order(r);
  const std::string what = r.bake ? "files" : "clips", one = r.bake ? "file" : "clip";
  const std::string title = "dqskin diff " + r.a + " " + r.b;
  std::string h = "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>" + text(title) +
                  "</title><meta name=\"viewport\" content=\"width=device-width\"><style>" + diff_detail::kStyle +
                  kGeometryStyle + "</style></head><body>\n";
  size_t counts[3] = {0, 0, 0};
  for (const ClipGeometryDiff& c : r.clips) ++counts[int(c.status)];
  const DiffStatus overall = r.status();
  h += "<header id=\"index\" class=\"" + status_class(overall) + "\"><h1><span class=\"status\">" + status_name(overall) +
       "</span> " + text(title) + "</h1><p>" + std::to_string(r.clips.size()) + " " + what + ": " +
       std::to_string(counts[2]) + " fail, " + std::to_string(counts[1]) + " warn, " + std::to_string(counts[0]) +
       " pass. " + (r.bake ? "Bakes compared file by file, meshes vertex by vertex and textures texel by texel (no pictures: a bake holds no rig to draw)"
                                                   : "Deformed surfaces compared frame by frame") +
       ", distances in scene units. Failing first, then by error relative to the " + one + "'s size.</p>\n" +
       header_facts(r) + "\n<table><tr><th></th><th>" + one + "</th><th>max error</th><th>reason</th></tr>\n";
  for (size_t k = 0; k < order.size(); ++k) {
    const ClipGeometryDiff& c = r.clips[order[k]];
    h += "<tr class=\"" + status_class(c.status) + "\"><td><span class=\"status\">" + status_name(c.status) +
         "</span></td><td><a href=\"#p" + std::to_string(k) + "\">" + text(c.name) + "</a></td><td>" + text(max_text(c)) +
         "</td><td>" + text(c.reason) + "</td></tr>\n";
  }
  h += "</table>" + findings_list(r) + "</header>\n";
  for (size_t k = 0; k < order.size(); ++k) {
    const ClipGeometryDiff& c = r.clips[order[k]];
    h += "<section id=\"p" + std::to_string(k) + "\" class=\"pair " + status_class(c.status) + "\" data-name=\"" +
         attribute(c.name) + "\" data-status=\"" + status_name(c.status) + "\"><h2><span class=\"status\">" +
         status_name(c.status) + "</span> " + one + " " + text(c.name) + "</h2>";
    if (!c.reason.empty()) h += "<p>" + text(c.reason) + "</p>";
    h += "<table class=\"figures\">" + figures_rows(r, c) + "</table>";
    if (!c.page_a.empty() && !c.page_b.empty()) {
      const std::string at = "t = " + number(c.worst.time) + " s";
      h += "<div class=\"views\"><figure><figcaption>" + text("A (reference) at " + at + ", shaded by its distance to B") +
           "</figcaption><img class=\"a\" loading=\"lazy\" src=\"" + attribute(c.page_a) +
           "\" alt=\"A\"></figure><figure><figcaption>" + text("B (candidate) at " + at + ", shaded by its distance to A") +
           "</figcaption><img class=\"b\" loading=\"lazy\" src=\"" + attribute(c.page_b) + "\" alt=\"B\"></figure></div>";
      h += "<p class=\"note\">Both framed alike, on one colour scale (0 to the clip's max error): the toggle and the swipe "
           "show what moved.</p>" + diff_detail::compare_box(c.page_a, c.page_b);
    }
    if (c.frames.size() > 1) h += error_chart(r, c);
    if (!c.joints.empty()) h += joints_table(c);
    h += diff_detail::section_nav(k, order.size()) + "</section>\n";
  }
  h += "<script>" + std::string(diff_detail::kScript) + "</script>\n</body></html>\n";
  return h;
}

}  // namespace dqskin
