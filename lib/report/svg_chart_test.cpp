// The SVG charts of the report page: decimation that keeps peaks, nulls as gaps, path data, escaping.
#include "svg_chart.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace dqskin::report_detail {
namespace {

size_t count(const std::string& text, const std::string& what) {
  size_t n = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + what.size())) ++n;
  return n;
}

// (Strings moved in, not assigned from literals: GCC 12's false -Wrestrict.)
ChartSpec chart(std::string title, std::string unit, std::vector<double> x, std::vector<ChartLine> lines) {
  ChartSpec spec;
  spec.title = std::move(title);
  spec.y_unit = std::move(unit);
  spec.x = std::move(x);
  spec.lines = std::move(lines);
  return spec;
}

// A BrainStem-sized clip: 1,047 frames of a wavy line with one sharp peak and one sharp dip, one frame each.
struct LongClip {
  std::vector<double> x;
  std::vector<std::optional<double>> values;
  LongClip() {
    for (int i = 0; i < 1047; ++i) {
      x.push_back(i / 30.0);
      values.push_back(0.01 + 0.002 * std::sin(i * 0.37));
    }
    values[517] = 0.25;
    values[800] = -0.1;
  }
};

TEST(SvgChart, DecimationKeepsThePeaksAndAtMostTwoPointsPerBucket) {
  const LongClip clip;
  const auto runs = decimated_runs(clip.x, clip.values, clip.x.front(), clip.x.back(), 300);
  ASSERT_EQ(runs.size(), 1u);
  EXPECT_LE(runs[0].size(), 600u);
  EXPECT_GT(runs[0].size(), 300u);  // the frames do fill every bucket
  bool peak = false, dip = false;
  for (const ChartPoint& p : runs[0]) {
    peak |= p.y == 0.25 && p.x == clip.x[517];
    dip |= p.y == -0.1 && p.x == clip.x[800];
  }
  EXPECT_TRUE(peak);
  EXPECT_TRUE(dip);
  for (size_t i = 1; i < runs[0].size(); ++i) EXPECT_LT(runs[0][i - 1].x, runs[0][i].x);
}

TEST(SvgChart, DecimationKeepsShortSeriesWholeAndBreaksLinesAtNulls) {
  const std::vector<double> x = {0, 1, 2, 3, 4, 5};
  const std::vector<std::optional<double>> values = {1, 2, std::nullopt, 4, 5, std::nullopt};
  const auto runs = decimated_runs(x, values, 0, 5, 300);
  ASSERT_EQ(runs.size(), 2u);
  ASSERT_EQ(runs[0].size(), 2u);
  ASSERT_EQ(runs[1].size(), 2u);
  EXPECT_EQ(runs[0][1].y, 2);
  EXPECT_EQ(runs[1][0].x, 3);
  EXPECT_TRUE(decimated_runs(x, {std::nullopt, std::nullopt}, 0, 5, 300).empty());
}

TEST(SvgChart, DrawsOneShapePerRunALegendAndTheUnits) {
  ChartSpec spec = chart("Distance <to> dib", "m", {0, 0.1, 0.2, 0.3},
                         {{"lbs", "lbs", {0.1, 0.2, 0.3, 0.2}}, {"dqs & co", "dqs", {0.01, std::nullopt, 0.02, 0.03}}});
  spec.include_zero = true;
  spec.marker_x = 0.2;
  spec.marker_label = std::string("worst");
  const std::string svg = line_chart_svg(spec);
  EXPECT_EQ(svg.rfind("<svg class=\"chart\"", 0), 0u);
  EXPECT_EQ(count(svg, "<path class=\"lbs\""), 1u);
  EXPECT_EQ(count(svg, "<path class=\"dqs\""), 1u);         // 0.02, 0.03
  EXPECT_EQ(count(svg, "<circle class=\"dqs dot\""), 1u);   // 0.01 alone between the start and a null
  EXPECT_NE(svg.find("Distance &lt;to&gt; dib"), std::string::npos);
  EXPECT_NE(svg.find(">dqs &amp; co</text>"), std::string::npos);
  EXPECT_NE(svg.find(">time (s)</text>"), std::string::npos);
  EXPECT_NE(svg.find(">m</text>"), std::string::npos);
  EXPECT_NE(svg.find("class=\"marker\""), std::string::npos);
  EXPECT_EQ(svg.find("no data"), std::string::npos);
  EXPECT_EQ(svg, line_chart_svg(spec));
}

// Relative steps in tenths: adding them up gives back the rounded points, however many there are.
TEST(SvgChart, PathStepsAddUpToTheRoundedPoints) {
  EXPECT_EQ(relative_path({{50, 100}, {50.5, 98.8}, {51.04, 98.8}, {52, 101.25}, {60, 101.25}}),
            "M50 100l.5-1.2 .5 0 1 2.5 8 0");
  EXPECT_EQ(relative_path({{1.2, 3.4}, {1.23, 3.38}}), "M1.2 3.4l");  // the same tenth: no step
  std::vector<std::pair<double, double>> points;
  for (int i = 0; i <= 1000; ++i) points.emplace_back(50 + 0.3 * i, 100 + 40 * std::sin(i * 0.37));
  const std::string d = relative_path(points);
  // Sum the steps: numbers after "l", separated by spaces or by a minus sign.
  long sum[2] = {0, 0};
  int axis = 0;
  const std::string steps = d.substr(d.find('l') + 1);
  for (size_t i = 0; i < steps.size();) {
    size_t end = i + 1;
    while (end < steps.size() && steps[end] != ' ' && steps[end] != '-') ++end;
    sum[axis] += std::lround(std::stod(steps.substr(i, end - i)) * 10);
    axis = 1 - axis;
    i = end < steps.size() && steps[end] == ' ' ? end + 1 : end;
  }
  EXPECT_EQ(sum[0], std::lround(points.back().first * 10) - 500);
  EXPECT_EQ(sum[1], std::lround(points.back().second * 10) - 1000);
}

TEST(SvgChart, SaysNoDataWhenEveryValueIsNull) {
  ChartSpec spec = chart("Joint angles", "\xC2\xB0", {0, 1}, {{"twist", "twist", {std::nullopt, std::nullopt}}});
  spec.reference_y = 1.0;
  const std::string svg = line_chart_svg(spec);
  EXPECT_NE(svg.find(">no data</text>"), std::string::npos);
  EXPECT_EQ(svg.find("<path class=\"twist\""), std::string::npos);
  EXPECT_EQ(svg.find("class=\"reference\""), std::string::npos);
  spec.lines[0].values[1] = 0.5;
  EXPECT_NE(line_chart_svg(spec).find("class=\"reference\""), std::string::npos);
}

TEST(SvgChart, ALongClipStaysSmall) {
  const LongClip clip;
  const ChartSpec spec = chart("Distance to dib", "m", clip.x,
                               {{"lbs", "lbs", clip.values}, {"dqs", "dqs", clip.values}, {"dib", "dib", clip.values}});
  const std::string svg = line_chart_svg(spec);
  // 3 lines of at most 600 points of at most 9 characters, and the frame.
  EXPECT_LT(svg.size(), 3u * 600 * 9 + 4000) << svg.size();
  for (const char* line : {"lbs", "dqs", "dib"}) EXPECT_EQ(count(svg, "<path class=\"" + std::string(line) + "\""), 1u) << line;
}

}  // namespace
}  // namespace dqskin::report_detail
