// The page of a geometric diff on built reports: the order of its sections, the chart of each clip (one
// point per frame, the thresholds where they fall, a NaN frame a gap), escaping, and the bake's page. The
// browser check (diff_page_check.mjs, app/tests/diff.cmake) opens a real one.
#include "dqskin/diff_page.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

namespace dqskin {
namespace {

size_t occurrences(const std::string& text, const std::string& what) {
  size_t n = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + what.size())) ++n;
  return n;
}

// The part of the page from section `id` to the end of that section.
std::string section(const std::string& page, const std::string& id) {
  const size_t start = page.find("<section id=\"" + id + "\"");
  if (start == std::string::npos) return "";
  return page.substr(start, page.find("</section>", start) - start);
}

ClipGeometryDiff clip(const std::string& name, DiffStatus status, double max_error, size_t frames) {
  ClipGeometryDiff c;
  c.name = c.name_b = name;
  c.status = status;
  c.diagonal = 2.0;
  c.max_error = max_error;
  c.worst = {'A', 7, 0.5, "elbow"};
  for (size_t f = 0; f < frames; ++f) {
    FrameDiff d;
    d.time = double(f) / 4;
    d.max_error = f == 2 ? max_error : max_error / 4;
    d.p99_error = d.max_error / 2, d.mean_error = d.max_error / 8;
    d.worst_joint = "elbow";
    c.frames.push_back(d);
  }
  c.joints = {{"elbow", max_error, 0.5}, {"shoulder", max_error / 2, 0.25}};
  c.samples = 100;
  if (status != DiffStatus::kPass) c.reason = "something over a threshold";
  return c;
}

GeometryDiffReport report() {
  GeometryDiffReport r;
  r.a = "a.glb", r.b = "b.glb";
  r.deformer = "cpu";
  r.identity = true;
  r.thresholds.fail = 0.02, r.thresholds.warn = 0.01;
  r.clips = {clip("Idle", DiffStatus::kPass, 0.001, 5), clip("Walk & <Run>", DiffStatus::kFail, 0.0349, 5),
             clip("Wave", DiffStatus::kWarn, 0.015, 5), clip("Jump", DiffStatus::kFail, 0.09, 5)};
  r.clips[1].page_a = "images/clip0001.a.png", r.clips[1].page_b = "images/clip0001.b.png";
  return r;
}

TEST(GeometryPage, FailuresFirstThenByRelativeErrorThenWarningsThenPasses) {
  const std::string page = geometry_page_html(report());
  EXPECT_NE(section(page, "p0").find("data-name=\"Jump\""), std::string::npos);
  EXPECT_NE(section(page, "p1").find("data-name=\"Walk &amp; &lt;Run&gt;\""), std::string::npos);
  EXPECT_NE(section(page, "p2").find("data-status=\"WARN\""), std::string::npos);
  EXPECT_NE(section(page, "p3").find("data-name=\"Idle\""), std::string::npos);
  EXPECT_EQ(section(page, "p4"), "");
  EXPECT_EQ(page.find("<Run>"), std::string::npos);  // escaped everywhere
  // Links: the index to every section, each section to its neighbours.
  for (const char* link : {"href=\"#p0\"", "href=\"#p3\""}) EXPECT_NE(page.find(link), std::string::npos);
  EXPECT_NE(section(page, "p3").find("href=\"#p2\""), std::string::npos);
  EXPECT_EQ(section(page, "p3").find("href=\"#p4\""), std::string::npos);
}

TEST(GeometryPage, PicturesAndTheirToggleWhereTheClipHasThem) {
  const std::string page = geometry_page_html(report());
  const std::string walk = section(page, "p1"), jump = section(page, "p0");
  EXPECT_NE(walk.find("src=\"images/clip0001.a.png\""), std::string::npos);
  EXPECT_NE(walk.find("src=\"images/clip0001.b.png\""), std::string::npos);
  EXPECT_NE(walk.find("class=\"compare\""), std::string::npos);
  EXPECT_EQ(jump.find("<img"), std::string::npos);
  EXPECT_EQ(jump.find("class=\"compare\""), std::string::npos);
}

TEST(GeometryPage, ChartHasAPointPerFrameAndTheThresholdsWithinItsAxis) {
  const std::string walk = section(geometry_page_html(report()), "p1");
  EXPECT_EQ(occurrences(walk, "<circle class=\"frame\""), 5u);
  // Peak 3.49 cm: the axis runs to 5 cm, so --fail (2 cm) and --warn (1 cm) are lines on it.
  EXPECT_NE(walk.find(">5 cm</text>"), std::string::npos);
  EXPECT_EQ(occurrences(walk, "<line class=\"threshold\""), 2u);
  EXPECT_NE(walk.find(">--fail</text>"), std::string::npos);
  EXPECT_NE(walk.find(">--warn</text>"), std::string::npos);
  // Idle's peak is 1 mm: the thresholds are far above its axis and named below it instead.
  const std::string idle = section(geometry_page_html(report()), "p3");
  EXPECT_EQ(occurrences(idle, "<line class=\"threshold\""), 0u);
  EXPECT_NE(idle.find("above the chart: --fail 2 cm, --warn 1 cm"), std::string::npos);
}

TEST(GeometryPage, EqualThresholdsShareOneLineAndRelativeOnesScaleWithTheClip) {
  GeometryDiffReport r = report();
  r.relative = true;
  r.thresholds.fail = r.thresholds.warn = 0.01;  // 2 cm on the clips' 2 m diagonal
  const std::string walk = section(geometry_page_html(r), "p1");
  EXPECT_EQ(occurrences(walk, "<line class=\"threshold\""), 1u);
  EXPECT_NE(walk.find(">--fail, --warn</text>"), std::string::npos);
  EXPECT_NE(walk.find("--fail 0.01 (2 cm), --warn 0.01 (2 cm) of the diagonal"), std::string::npos);
}

TEST(GeometryPage, AFrameThatIsNotFiniteBreaksTheLines) {
  GeometryDiffReport r = report();
  r.clips[3].frames[3].max_error = std::numeric_limits<double>::quiet_NaN();
  const std::string jump = section(geometry_page_html(r), "p0");
  const size_t max_path = jump.find("<path class=\"max\" d=\"");
  ASSERT_NE(max_path, std::string::npos);
  const std::string d = jump.substr(max_path, jump.find("\"/>", max_path) - max_path);
  EXPECT_EQ(occurrences(d, "M"), 2u);  // frames 0-2, then frame 4 alone
  EXPECT_EQ(occurrences(d, "L"), 2u);
  EXPECT_EQ(d.find("nan"), std::string::npos);
}

TEST(GeometryPage, ABakesPageListsFilesWithoutPicturesOrCharts) {
  GeometryDiffReport r;
  r.bake = true;
  r.a = "golden", r.b = "out";
  ClipGeometryDiff ply = clip("arm/bend/frame_0001.ply", DiffStatus::kFail, 0.03, 1);
  ClipGeometryDiff missing;
  missing.name = missing.name_b = "arm/bend/frame_0002.ply";
  missing.status = DiffStatus::kFail;
  missing.reason = "missing in B";
  r.clips = {ply, missing};
  const std::string page = geometry_page_html(r);
  EXPECT_NE(page.find("2 files: 2 fail, 0 warn, 0 pass"), std::string::npos);
  EXPECT_NE(section(page, "p0").find("missing in B"), std::string::npos);  // not compared: first
  EXPECT_NE(section(page, "p1").find("vertex 7"), std::string::npos);
  EXPECT_EQ(page.find("<svg"), std::string::npos);
  EXPECT_EQ(page.find("<img"), std::string::npos);
}

TEST(GeometryPage, TheSameReportGivesTheSameBytes) {
  EXPECT_EQ(geometry_page_html(report()), geometry_page_html(report()));
}

}  // namespace
}  // namespace dqskin
