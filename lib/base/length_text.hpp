// Lengths in scene units (glTF's meters) with an SI prefix, one spelling for every message and report that
// prints one: the bake's texture planner and checks, the geometric diff's reports and heat-map legends.
#pragma once

#include <cstdio>
#include <string>

namespace dqskin {

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

}  // namespace dqskin
