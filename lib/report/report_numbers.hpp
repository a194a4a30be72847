// How the HTML page of `dqskin report` writes numbers (internal to lib/report): one fixed, locale-independent
// rule (std::to_chars), so that the same report.json gives the same bytes, and so that the browser check
// (report_check.mjs, which repeats the rule) can tell a cell's text from the JSON number it stands for.
#pragma once

#include <string>

namespace dqskin::report_detail {

// A number as the page shows it, 3 significant digits:
//   0 and integers below 1e15 in magnitude: all their digits ("0", "143", "1047");
//   1e-4 <= |v| < 1e15: fixed notation with 2 - floor(log10 |v|) decimals, at least 0 ("0.0120",
//     "0.930", "12.5", "170"); the decimals come from comparisons with powers of ten, not from log10,
//     so that another language finds the same count;
//   otherwise: scientific with 2 decimals and a bare exponent ("1.23e-5", "4.00e15").
// Rounding is to nearest, ties to even (std::to_chars on the exact binary value).
std::string shown_number(double value);

// An SVG coordinate: fixed, 1 decimal, without a trailing ".0" and without "-0".
std::string svg_number(double value);

}  // namespace dqskin::report_detail
