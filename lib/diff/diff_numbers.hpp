// Numbers as `dqskin diff` prints them, in verdict reasons, heat-map descriptions and every report format
// (internal to lib/diff): one spelling, so that a threshold reads the same in the text, the JSON reason
// and the JUnit properties.
#pragma once

#include "../base/length_text.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>

namespace dqskin::diff_detail {

// %g, with "inf", "-inf" and "nan" spelled the same on every platform.
inline std::string number(double value) {
  if (std::isnan(value)) return "nan";
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  char text[32];
  std::snprintf(text, sizeof text, "%g", value);
  return text;
}

// idiff's percentage: 3 significant digits.
inline std::string percent(uint64_t count, uint64_t pixels) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g%%", 100.0 * double(count) / double(std::max<uint64_t>(pixels, 1)));
  return text;
}

// Lengths with their unit, as the bake prints them too (base/length_text.hpp).
using dqskin::length_text;
using dqskin::length_with_unit;

// A length in scene units with the SI prefix that suits it: "3.1 mm"; "0 m" for zero.
inline std::string scene_length(double value) {
  if (!std::isfinite(value)) return number(value);
  return value == 0 ? "0 m" : length_with_unit(value, value);
}

}  // namespace dqskin::diff_detail
