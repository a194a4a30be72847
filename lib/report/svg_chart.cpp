// Line charts as inline SVG (svg_chart.hpp): ranges, round ticks, min/max decimation, relative path data.
#include "svg_chart.hpp"
#include "report_numbers.hpp"
#include "../base/xml_escape.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>

namespace dqskin::report_detail {
namespace {

// The chart's box in SVG units: the plot area is kPlotWidth pixels wide at the page's natural size, one
// decimation bucket per pixel.
constexpr double kWidth = 360, kHeight = 196;
constexpr double kLeft = 50, kRight = 10, kTop = 34, kBottom = 30;
constexpr int kPlotWidth = int(kWidth - kLeft - kRight);
constexpr double kPlotHeight = kHeight - kTop - kBottom;

std::string text(const std::string& s) { return io::xml(s, false); }
std::string attribute(const std::string& s) { return io::xml(s, true); }

// Ticks at multiples of a round step (1, 2 or 5 times a power of ten) giving about `count` intervals over
// [lo, hi]; `decimals` is what a label needs to show the step.
struct Ticks {
  double step = 1;
  int decimals = 0;
};
Ticks round_ticks(double lo, double hi, int count) {
  const double raw = (hi - lo) / count;
  double power = 1;
  int decimals = 0;
  while (power > raw) power /= 10, ++decimals;
  while (power * 10 <= raw) power *= 10, --decimals;
  Ticks t;
  t.step = power;
  if (raw > 5 * power) t.step = 10 * power, --decimals;
  else if (raw > 2 * power) t.step = 5 * power;
  else if (raw > power) t.step = 2 * power;
  t.decimals = std::max(0, decimals);
  return t;
}

std::string tick_label(double value, int decimals) {
  char buffer[64];
  const auto end = std::to_chars(buffer, buffer + sizeof buffer, value, std::chars_format::fixed, decimals).ptr;
  const std::string s(buffer, end);
  return s.find_first_not_of("-0.") == std::string::npos ? std::string("0") : s;  // "-0.00" is 0
}

// A number of tenths as SVG path data writes it, shortest: 5 -> ".5", -12 -> "-1.2", 30 -> "3".
std::string tenths(long v) {
  std::string s = v < 0 ? "-" : "";
  const long a = v < 0 ? -v : v;
  if (a >= 10) s += std::to_string(a / 10);
  if (a % 10 != 0) {
    s += '.';
    s += char('0' + a % 10);
  }
  if (a == 0) s += "0";
  return s;
}

}  // namespace

std::string relative_path(const std::vector<std::pair<double, double>>& points) {
  std::string d;
  long x = 0, y = 0;
  for (size_t i = 0; i < points.size(); ++i) {
    const long nx = std::lround(points[i].first * 10), ny = std::lround(points[i].second * 10);
    if (i == 0) {
      d += 'M';
      d += tenths(nx) + " " + tenths(ny) + "l";
    } else {
      if (nx == x && ny == y) continue;  // the same pixel tenth: nothing to draw
      for (const long step : {nx - x, ny - y}) {
        const std::string number = tenths(step);
        if (d.back() != 'l' && number[0] != '-') d += ' ';
        d += number;
      }
    }
    x = nx, y = ny;
  }
  return d;
}

std::vector<ChartRun> decimated_runs(const std::vector<double>& x, const std::vector<std::optional<double>>& values,
                                     double x_min, double x_max, int buckets) {
  std::vector<ChartRun> runs;
  const size_t n = std::min(x.size(), values.size());
  const double span = x_max > x_min ? x_max - x_min : 1;
  const auto bucket_of = [&](size_t i) {
    return std::clamp(int(std::floor((x[i] - x_min) / span * buckets)), 0, std::max(0, buckets - 1));
  };
  bool in_run = false;
  size_t i = 0;
  while (i < n) {
    if (!values[i] || !std::isfinite(*values[i]) || !std::isfinite(x[i])) {
      in_run = false;
      ++i;
      continue;
    }
    if (!in_run) runs.emplace_back(), in_run = true;
    // The points of this run in i's bucket: keep the lowest and the highest, in index order.
    const int bucket = bucket_of(i);
    size_t low = i, high = i, j = i;
    for (; j < n && values[j] && std::isfinite(*values[j]) && std::isfinite(x[j]) && bucket_of(j) == bucket; ++j) {
      if (*values[j] < *values[low]) low = j;
      if (*values[j] > *values[high]) high = j;
    }
    const size_t first = std::min(low, high), second = std::max(low, high);
    runs.back().push_back({x[first], *values[first]});
    if (second != first) runs.back().push_back({x[second], *values[second]});
    i = j;
  }
  return runs;
}

std::string line_chart_svg(const ChartSpec& spec) {
  // Ranges: x over the clip's times, y over every value (with 0 and the reference line when asked).
  double x_min = 0, x_max = 0;
  if (!spec.x.empty()) x_min = spec.x.front(), x_max = spec.x.back();
  if (!(x_max > x_min)) x_max = x_min + 1;
  bool any = false;
  double y_min = 0, y_max = 0;
  const auto widen = [&](double v) {
    if (!std::isfinite(v)) return;
    if (!any) y_min = y_max = v, any = true;
    y_min = std::min(y_min, v), y_max = std::max(y_max, v);
  };
  for (const ChartLine& line : spec.lines)
    for (size_t i = 0; i < std::min(line.values.size(), spec.x.size()); ++i)
      if (line.values[i]) widen(*line.values[i]);
  const bool has_data = any;
  if (spec.include_zero) widen(0);
  if (spec.reference_y) widen(*spec.reference_y);
  if (!any) y_min = 0, y_max = 1;
  if (!(y_max > y_min)) {
    const double pad = y_min == 0 ? 1 : std::fabs(y_min) * 0.1;
    y_min -= pad, y_max += pad;
  }
  const Ticks y_ticks = round_ticks(y_min, y_max, 4);
  y_min = std::floor(y_min / y_ticks.step) * y_ticks.step;
  y_max = std::ceil(y_max / y_ticks.step) * y_ticks.step;
  const Ticks x_ticks = round_ticks(x_min, x_max, 5);

  const auto px = [&](double x) { return kLeft + (x - x_min) / (x_max - x_min) * kPlotWidth; };
  const auto py = [&](double y) { return kTop + kPlotHeight - (y - y_min) / (y_max - y_min) * kPlotHeight; };
  const std::string plot_bottom = svg_number(kTop + kPlotHeight), plot_right = svg_number(kLeft + kPlotWidth);

  std::string s = "<svg class=\"chart\" xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"0 0 " + svg_number(kWidth) + " " +
                  svg_number(kHeight) + "\" width=\"" + svg_number(kWidth) + "\" height=\"" + svg_number(kHeight) +
                  "\" role=\"img\" aria-label=\"" + attribute(spec.title) + "\">\n";
  s += "<text class=\"title\" x=\"4\" y=\"13\">" + text(spec.title) + "</text>\n";
  s += "<text class=\"unit\" x=\"" + svg_number(kLeft - 6) + "\" y=\"" + svg_number(kTop - 8) +
       "\" text-anchor=\"end\">" + text(spec.y_unit) + "</text>\n";
  // Legend on the row above the plot, one short line and name per line.
  double legend_x = kLeft + 4;
  for (const ChartLine& line : spec.lines) {
    const std::string y = svg_number(kTop - 12);
    s += "<line class=\"" + attribute(line.css_class) + "\" x1=\"" + svg_number(legend_x) + "\" y1=\"" + y + "\" x2=\"" +
         svg_number(legend_x + 16) + "\" y2=\"" + y + "\"/>";
    s += "<text class=\"legend\" x=\"" + svg_number(legend_x + 20) + "\" y=\"" + svg_number(kTop - 8) + "\">" +
         text(line.label) + "</text>\n";
    legend_x += 28 + 6.2 * double(line.label.size());
  }
  // Grid and tick labels.
  for (long k = long(std::ceil(y_min / y_ticks.step - 1e-9)); double(k) * y_ticks.step <= y_max + 1e-9 * y_ticks.step; ++k) {
    const double v = double(k) * y_ticks.step;
    const std::string y = svg_number(py(v));
    s += "<line class=\"grid\" x1=\"" + svg_number(kLeft) + "\" y1=\"" + y + "\" x2=\"" + plot_right + "\" y2=\"" + y + "\"/>";
    s += "<text class=\"tick\" x=\"" + svg_number(kLeft - 4) + "\" y=\"" + svg_number(py(v) + 3.5) +
         "\" text-anchor=\"end\">" + tick_label(v, y_ticks.decimals) + "</text>\n";
  }
  for (long k = long(std::ceil(x_min / x_ticks.step - 1e-9)); double(k) * x_ticks.step <= x_max + 1e-9 * x_ticks.step; ++k) {
    const double v = double(k) * x_ticks.step;
    const std::string x = svg_number(px(v));
    s += "<line class=\"axis\" x1=\"" + x + "\" y1=\"" + plot_bottom + "\" x2=\"" + x + "\" y2=\"" +
         svg_number(kTop + kPlotHeight + 4) + "\"/>";
    s += "<text class=\"tick\" x=\"" + x + "\" y=\"" + svg_number(kTop + kPlotHeight + 14) + "\" text-anchor=\"middle\">" +
         tick_label(v, x_ticks.decimals) + "</text>\n";
  }
  s += "<text class=\"unit\" x=\"" + plot_right + "\" y=\"" + svg_number(kHeight - 3) + "\" text-anchor=\"end\">time (s)</text>\n";
  s += "<path class=\"axis\" d=\"M" + svg_number(kLeft) + " " + svg_number(kTop) + "V" + plot_bottom + "H" + plot_right + "\"/>\n";
  if (spec.reference_y && has_data) {  // with nothing to compare, the line would only cross out empty_text
    const std::string y = svg_number(py(*spec.reference_y));
    s += "<line class=\"reference\" x1=\"" + svg_number(kLeft) + "\" y1=\"" + y + "\" x2=\"" + plot_right + "\" y2=\"" + y + "\"/>\n";
  }
  if (spec.marker_x && *spec.marker_x >= x_min && *spec.marker_x <= x_max) {
    const std::string x = svg_number(px(*spec.marker_x));
    s += "<line class=\"marker\" x1=\"" + x + "\" y1=\"" + svg_number(kTop) + "\" x2=\"" + x + "\" y2=\"" + plot_bottom + "\"/>";
    s += "<text class=\"marker-label\" x=\"" + svg_number(px(*spec.marker_x) + 3) + "\" y=\"" + svg_number(kTop + 9) + "\">" +
         text(spec.marker_label) + "</text>\n";
  }
  if (!has_data) {
    s += "<text class=\"empty\" x=\"" + svg_number(kLeft + kPlotWidth / 2.0) + "\" y=\"" + svg_number(kTop + kPlotHeight / 2) +
         "\" text-anchor=\"middle\">" + text(spec.empty_text) + "</text>\n";
  }
  for (const ChartLine& line : spec.lines) {
    for (const ChartRun& run : decimated_runs(spec.x, line.values, x_min, x_max, kPlotWidth)) {
      // A run of one point (a value between two nulls) is a dot, not an invisible line.
      if (run.size() == 1) {
        s += "<circle class=\"" + attribute(line.css_class) + " dot\" cx=\"" + svg_number(px(run[0].x)) + "\" cy=\"" +
             svg_number(py(run[0].y)) + "\" r=\"1.5\"/>\n";
        continue;
      }
      std::vector<std::pair<double, double>> points;
      for (const ChartPoint& p : run) points.emplace_back(px(p.x), py(p.y));
      s += "<path class=\"" + attribute(line.css_class) + "\" d=\"" + relative_path(points) + "\"/>\n";
    }
  }
  s += "</svg>";
  return s;
}

}  // namespace dqskin::report_detail
