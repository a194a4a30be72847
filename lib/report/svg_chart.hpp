// Small inline SVG line charts for the HTML page of `dqskin report` (internal to lib/report): a quantity
// over a clip's time, one polyline per method, axes with ticks and units, a legend. Lines are styled by
// CSS class (the page's <style> gives lbs, dqs and dib their colours), so that every chart of the page
// uses the same three colours.
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace dqskin::report_detail {

struct ChartLine {
  std::string label;                          // legend text
  std::string css_class;                      // stroke colour and dash, from the page's style sheet
  std::vector<std::optional<double>> values;  // one per ChartSpec::x; nullopt breaks the line
};

struct ChartSpec {
  std::string title;
  std::string y_unit;                  // written above the y axis ("m", "ratio", "°")
  std::vector<double> x;               // seconds, increasing
  std::vector<ChartLine> lines;
  bool include_zero = false;           // the y range reaches down (or up) to 0
  std::optional<double> reference_y;   // a dashed horizontal line (1 for ratios to rest), inside the range;
                                       // not drawn when no line has a value
  std::optional<double> marker_x;      // a dashed vertical line (the worst frame's time)
  std::string marker_label;
  std::string empty_text = "no data";  // what an empty plot says
};

// The chart as an <svg> element (fixed size, scaled by CSS), deterministic. A chart without any value
// says "no data" in its plot area.
std::string line_chart_svg(const ChartSpec& spec);

// A run of a line between two nulls, in data coordinates.
struct ChartPoint {
  double x = 0, y = 0;
};
using ChartRun = std::vector<ChartPoint>;

// The runs of `values` over `x` with at most 2 points per run and bucket: [x_min, x_max] cut into
// `buckets` equal buckets (one per pixel of the plot), and of each run's points in a bucket only the
// lowest and the highest are kept, in their order, so that peaks survive (the chart of a 1,000-frame clip
// keeps its worst frame). Points are taken up to the shorter of x and values.
std::vector<ChartRun> decimated_runs(const std::vector<double>& x, const std::vector<std::optional<double>>& values,
                                     double x_min, double x_max, int buckets);

// SVG path data through `points` (SVG units): the first point absolute ("M"), then relative steps ("l"),
// each point rounded once to a tenth, so that the steps add up exactly to the rounded points and a point
// costs about 7 bytes where "x,y " costs 11. Points that round to the previous one are left out.
std::string relative_path(const std::vector<std::pair<double, double>>& points);

}  // namespace dqskin::report_detail
