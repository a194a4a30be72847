// The reports of a GeometryDiffReport (include/dqskin/geometry_report.hpp). Formatting only.
#include "dqskin/geometry_report.hpp"
#include "correspondence_pose.hpp"
#include "diff_numbers.hpp"
#include "../base/xml_escape.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>

namespace dqskin {
namespace {

using Json = nlohmann::ordered_json;
using diff_detail::number;
using diff_detail::percent;
using io::xml;

constexpr size_t kNotesShown = 10;

Json finite_or_null(double value) { return std::isfinite(value) ? Json(value) : Json(nullptr); }

std::string length(double value) { return diff_detail::scene_length(value); }

double relative(double value, double diagonal) { return diagonal > 0 ? value / diagonal : 0; }

// A bake's file: "STATUS  path, max E at vertex V (R of the diagonal D); p99 …, mean …[, normals …]".
std::string file_line(const ClipGeometryDiff& c) {
  std::string line = std::string(status_name(c.status)) + "  " + c.name;
  if (!c.frames.empty())
    line += ", max " + length(c.max_error) + " at " +
            (c.name.size() > 4 && c.name.compare(c.name.size() - 4, 4, ".exr") == 0 ? "texel " : "vertex ") +
            std::to_string(c.worst.vertex) + " (" +
            number(relative(c.max_error, c.diagonal)) + " of the diagonal " + length(c.diagonal) + "); p99 " +
            length(c.p99_error) + ", mean " + length(c.mean_error) + ", normals " + number(c.max_normal_degrees) + " deg";
  if (!c.reason.empty()) line += (c.frames.empty() ? ": " : "; ") + c.reason;
  return line + "\n";
}

std::string clip_line(const GeometryDiffReport& r, const ClipGeometryDiff& c) {
  if (r.bake) return file_line(c);
  std::string line = std::string(status_name(c.status)) + "  clip " + c.name;
  if (c.name_b != c.name) line += " (B: " + c.name_b + ")";
  line += ", t = " + number(c.worst.time) + " s, max " + length(c.max_error) + " at " + c.worst.joint + " (" +
          number(relative(c.max_error, c.diagonal)) + " of the diagonal " + length(c.diagonal) + "); p99 " +
          length(c.p99_error) + ", mean " + length(c.mean_error) + ", normals " + number(c.max_normal_degrees) +
          " deg; " + std::to_string(c.frames.size()) + " frames";
  if (!c.reason.empty()) line += "; " + c.reason;
  return line + "\n";
}

// A share as a percentage with 3 significant digits: "31.2%".
std::string share(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g%%", 100.0 * value);
  return text;
}

std::string threshold_unit(const GeometryDiffReport& r) { return r.relative ? " of the diagonal" : " scene units"; }

}  // namespace

std::string pose_text(const GeometryDiffReport& r) {
  if (r.correspondence_pose == "clip") return "clip " + r.correspondence_clip + ", t = " + number(r.correspondence_time) + " s";
  return "the " + r.correspondence_pose + " pose";
}

std::string geometry_text(const GeometryDiffReport& r) {
  if (r.bake) {
    std::string t = "A " + r.a + ", B " + r.b + ": bakes, " + std::to_string(r.clips.size()) + " files paired by path\n";
    size_t counts[3] = {0, 0, 0};
    for (const ClipGeometryDiff& c : r.clips) {
      ++counts[int(c.status)];
      t += clip_line(r, c);
    }
    return t + "summary: " + status_name(r.status()) + " (" + std::to_string(r.clips.size()) + " files: " +
           std::to_string(counts[0]) + " pass, " + std::to_string(counts[1]) + " warn, " + std::to_string(counts[2]) +
           " fail; thresholds --fail " + number(r.thresholds.fail) + ", --warn " + number(r.thresholds.warn) +
           threshold_unit(r) + ")\n";
  }
  std::string t = "A " + r.a + " (" + std::to_string(r.vertices_a) + " vertices), B " + r.b + " (" +
                  std::to_string(r.vertices_b) + " vertices); " + to_string(r.mode) + " on " + r.deformer + "\n";
  if (r.correspondence_pose == "rest") {
    t += r.identity ? "correspondence: the same vertices in the same order\n"
                    : "correspondence: closest surface points; at rest A to B max " +
                          length(r.rest_a_to_b) + ", B to A max " + length(r.rest_b_to_a) + "\n";
  } else {
    t += r.identity ? "correspondence: the same vertices in the same order at " + pose_text(r) + "\n"
                    : "correspondence: closest surface points at " + pose_text(r) + "; there A to B max " +
                          length(r.rest_a_to_b) + ", B to A max " + length(r.rest_b_to_a) + "\n";
    t += "      the rest pose is degenerate: it distorts " + share(r.rest_distortion_a) + " of A's triangles and " +
         share(r.rest_distortion_b) + " of B's against the bind pose (an edge over twice or under half its length, or "
         "the triangle turned over; degenerate over " + share(diff_detail::kDegenerateShare) + ")\n";
  }
  t += "normals: vertex normals at " + std::to_string(r.smooth_normals_a) + " of A's and " +
       std::to_string(r.smooth_normals_b) + " of B's vertices (one smooth normal in both files), face normals on " +
       std::to_string(r.face_normals_a) + " of A's and " + std::to_string(r.face_normals_b) +
       " of B's triangles (flat shading, split normals or no NORMAL)\n";
  if (r.on_no_triangle_a || r.on_no_triangle_b)
    t += "note: " + std::to_string(r.on_no_triangle_a) + " of A's " + std::to_string(r.vertices_a) + " vertices and " +
         std::to_string(r.on_no_triangle_b) + " of B's " + std::to_string(r.vertices_b) +
         " are on no triangle (unused, or of points and lines): not compared\n";
  for (const ClipGeometryDiff& c : r.clips) {
    t += clip_line(r, c);
    if (!c.joints.empty()) {
      t += "      worst joints:";
      for (size_t j = 0; j < c.joints.size() && j < 5; ++j)
        t += std::string(j ? "," : "") + " " + c.joints[j].joint + " " + length(c.joints[j].max_error) + " (t = " +
             number(c.joints[j].time) + " s)";
      t += "\n";
    }
    if (!c.heat_map.empty()) t += "      heat map " + c.heat_map + "\n";
  }
  if (!r.findings.empty()) {
    // Failures and warnings all; notes (an optimizer drops and resamples tracks by the dozen) the first ten.
    t += "animations:\n";
    size_t notes = 0;
    for (const AnimationFinding& f : r.findings) {
      if (f.severity == DiffStatus::kPass && ++notes > kNotesShown) continue;
      t += std::string("  ") + (f.severity == DiffStatus::kPass ? "note" : status_name(f.severity)) + "  clip " + f.clip +
           ": " + f.text + "\n";
    }
    if (notes > kNotesShown) t += "  ... and " + std::to_string(notes - kNotesShown) + " more notes (--json lists them all)\n";
  }
  if (!r.contact_sheet.empty()) t += "worst frames: " + r.contact_sheet + "\n";
  size_t counts[3] = {0, 0, 0};
  for (const ClipGeometryDiff& c : r.clips) ++counts[int(c.status)];
  t += std::string("summary: ") + status_name(r.status()) + " (" + std::to_string(r.clips.size()) + " clips: " +
       std::to_string(counts[0]) + " pass, " + std::to_string(counts[1]) + " warn, " + std::to_string(counts[2]) +
       " fail; thresholds --fail " + number(r.thresholds.fail) + ", --warn " + number(r.thresholds.warn) +
       threshold_unit(r) + ")\n";
  return t;
}

std::string geometry_json(const GeometryDiffReport& r) {
  const DiffThresholds& t = r.thresholds;
  Json doc;
  doc["a"] = r.a;
  doc["b"] = r.b;
  doc["kind"] = r.bake ? "bakes" : "gltf";
  doc["mode"] = to_string(r.mode);
  doc["deformer"] = r.deformer;
  doc["thresholds"] = {{"fail", finite_or_null(t.fail)},           {"fail_percent", t.fail_percent},
                       {"hard_fail", finite_or_null(t.hard_fail)}, {"warn", finite_or_null(t.warn)},
                       {"warn_percent", t.warn_percent},           {"hard_warn", finite_or_null(t.hard_warn)},
                       {"relative", r.relative}};
  // rest_a_to_b and rest_b_to_a: at the pose named by "pose" (the rest pose unless it is degenerate).
  doc["correspondence"] = {
      {"kind", r.identity ? "identity" : "closest-point"},
      {"pose", r.correspondence_pose},
      {"clip", r.correspondence_pose == "clip" ? Json(r.correspondence_clip) : Json(nullptr)},
      {"time", r.correspondence_pose == "clip" ? Json(r.correspondence_time) : Json(nullptr)},
      {"rest_distortion", {{"a", r.rest_distortion_a}, {"b", r.rest_distortion_b}, {"degenerate_over", diff_detail::kDegenerateShare}}},
      {"rest_a_to_b", r.rest_a_to_b},
      {"rest_b_to_a", r.rest_b_to_a},
      {"normals",
       {{"smooth_a", r.smooth_normals_a}, {"smooth_b", r.smooth_normals_b}, {"faces_a", r.face_normals_a}, {"faces_b", r.face_normals_b}}}};
  doc["vertices"] = {{"a", r.vertices_a},
                     {"b", r.vertices_b},
                     {"on_no_triangle_a", r.on_no_triangle_a},
                     {"on_no_triangle_b", r.on_no_triangle_b}};
  Json findings = Json::array();
  for (const AnimationFinding& f : r.findings)
    findings.push_back({{"severity", f.severity == DiffStatus::kPass ? "note" : status_name(f.severity)},
                        {"clip", f.clip},
                        {"text", f.text}});
  doc["findings"] = std::move(findings);
  Json clips = Json::array();
  for (const ClipGeometryDiff& c : r.clips) {
    Json j;
    j["name"] = c.name;
    j["name_b"] = c.name_b;
    j["status"] = status_name(c.status);
    j["reason"] = c.reason.empty() ? Json(nullptr) : Json(c.reason);
    j["diagonal"] = c.diagonal;
    j["max_error"] = finite_or_null(c.max_error);
    j["max_error_relative"] = finite_or_null(relative(c.max_error, c.diagonal));
    j["max_a_to_b"] = finite_or_null(c.max_a_to_b);
    j["max_b_to_a"] = finite_or_null(c.max_b_to_a);
    j["p99_error"] = finite_or_null(c.p99_error);
    j["mean_error"] = finite_or_null(c.mean_error);
    j["max_normal_degrees"] = c.max_normal_degrees;
    j["worst_time"] = c.worst.time;
    j["worst_joint"] = c.worst.joint;
    j["worst_vertex"] = {{"side", std::string(1, c.worst.side)}, {"index", c.worst.vertex}};
    j["samples"] = c.samples;
    j["over_warn"] = c.over_warn;
    j["over_fail"] = c.over_fail;
    Json joints = Json::array();
    for (const JointDiff& d : c.joints) joints.push_back({{"joint", d.joint}, {"max_error", finite_or_null(d.max_error)}, {"time", d.time}});
    j["joints"] = std::move(joints);
    Json frames = Json::array();
    for (const FrameDiff& f : c.frames)
      frames.push_back({{"time", f.time},
                        {"max_error", finite_or_null(f.max_error)},
                        {"max_error_relative", finite_or_null(relative(f.max_error, c.diagonal))},
                        {"p99_error", finite_or_null(f.p99_error)},
                        {"mean_error", finite_or_null(f.mean_error)},
                        {"max_normal_degrees", f.max_normal_degrees},
                        {"worst_joint", f.worst_joint}});
    j["frames"] = std::move(frames);
    j["heat_map"] = c.heat_map.empty() ? Json(nullptr) : Json(c.heat_map);
    clips.push_back(std::move(j));
  }
  doc["clips"] = std::move(clips);
  doc["contact_sheet"] = r.contact_sheet.empty() ? Json(nullptr) : Json(r.contact_sheet);
  doc["status"] = status_name(r.status());
  return doc.dump(2, ' ', false, Json::error_handler_t::replace) + "\n";
}

std::string geometry_junit(const GeometryDiffReport& r) {
  size_t tests = r.clips.size(), failures = 0;
  for (const ClipGeometryDiff& c : r.clips) failures += c.status == DiffStatus::kFail;
  std::string notes, cases;
  for (const AnimationFinding& f : r.findings) {
    if (f.severity == DiffStatus::kPass) {
      notes += "clip " + f.clip + ": " + f.text + "\n";
      continue;
    }
    ++tests;
    cases += "    <testcase classname=\"dqskin.diff.geometry\" name=\"" + xml("clip " + f.clip + " (animation)", true) + "\">\n";
    if (f.severity == DiffStatus::kFail) {
      ++failures;
      cases += "      <failure type=\"FAIL\" message=\"" + xml(f.text, true) + "\"/>\n";
    } else {
      cases += "      <system-out>" + xml("WARN: " + f.text, false) + "</system-out>\n";
    }
    cases += "    </testcase>\n";
  }
  for (const ClipGeometryDiff& c : r.clips) {
    cases += "    <testcase classname=\"dqskin.diff.geometry\" name=\"" + xml(r.bake ? c.name : "clip " + c.name, true) + "\"";
    if (c.status == DiffStatus::kPass) {
      cases += "/>\n";
      continue;
    }
    const std::string line = clip_line(r, c) + (c.heat_map.empty() ? "" : "heat map: " + c.heat_map + "\n");
    cases += ">\n";
    if (c.status == DiffStatus::kFail)
      cases += "      <failure type=\"FAIL\" message=\"" + xml(c.reason, true) + "\">" + xml(line, false) + "</failure>\n";
    else
      cases += "      <system-out>" + xml("WARN: " + line, false) + "</system-out>\n";
    cases += "    </testcase>\n";
  }
  const std::string n = std::to_string(tests), f = std::to_string(failures);
  std::string x = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  x += "<testsuites name=\"dqskin diff\" tests=\"" + n + "\" failures=\"" + f + "\" errors=\"0\">\n";
  x += "  <testsuite name=\"" + xml("dqskin diff " + r.a + " " + r.b, true) + "\" tests=\"" + n + "\" failures=\"" + f +
       "\" errors=\"0\" skipped=\"0\">\n";
  x += "    <properties>\n";
  const std::pair<const char*, std::string> properties[] = {
      {"a", r.a}, {"b", r.b}, {"mode", to_string(r.mode)}, {"fail", number(r.thresholds.fail)},
      {"failpercent", number(r.thresholds.fail_percent)}, {"warn", number(r.thresholds.warn)},
      {"relative", r.relative ? "true" : "false"}};
  for (const auto& [name, value] : properties)
    x += "      <property name=\"" + std::string(name) + "\" value=\"" + xml(value, true) + "\"/>\n";
  x += "    </properties>\n" + cases;
  if (!notes.empty()) x += "    <system-out>" + xml(notes, false) + "</system-out>\n";
  x += "  </testsuite>\n</testsuites>\n";
  return x;
}

}  // namespace dqskin
