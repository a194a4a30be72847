// Numbers as `dqskin diff` prints them, in verdict reasons, heat-map descriptions and every report format
// (internal to lib/diff): one spelling, so that a threshold reads the same in the text, the JSON reason
// and the JUnit properties.
#pragma once

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

// A length in scene units (glTF's meters) with the SI prefix that suits `scale`, as the geometric diff's
// reports and heat-map legends print it: "3.1 mm", "250 um", "1.2 m".
inline std::string length_with_unit(double value, double scale) {
  struct Unit {
    double size;
    const char* name;
  };
  static const Unit units[] = {{1, "m"}, {1e-2, "cm"}, {1e-3, "mm"}, {1e-6, "um"}};
  const Unit* unit = &units[3];
  for (const Unit& u : units)
    if (scale >= u.size) {
      unit = &u;
      break;
    }
  char text[48];
  std::snprintf(text, sizeof text, "%.3g %s", value / unit->size, unit->name);
  return text;
}

// A length with the SI prefix that suits itself: "3.1 mm" (the bake's texture messages).
inline std::string length_text(double value) { return length_with_unit(value, value); }

}  // namespace dqskin::diff_detail
