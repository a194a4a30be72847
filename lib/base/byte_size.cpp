#include "byte_size.hpp"

#include "dqskin/error.hpp"

#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iterator>

namespace dqskin {

std::string byte_size(uint64_t bytes) {
  static const char* const units[] = {"KiB", "MiB", "GiB", "TiB", "PiB", "EiB"};
  if (bytes < 1024) return std::to_string(bytes) + (bytes == 1 ? " byte" : " bytes");
  double value = double(bytes) / 1024;
  size_t unit = 0;
  while (value >= 1024 && unit + 1 < std::size(units)) value /= 1024, ++unit;
  char text[32];
  std::snprintf(text, sizeof text, value < 10 ? "%.2f %s" : value < 100 ? "%.1f %s" : "%.0f %s", value, units[unit]);
  return text;
}

uint64_t parse_byte_size(const std::string& text, const std::string& what) {
  const std::string problem = what + " '" + text + "' is not a size in bytes (e.g. 2G, 512M, 1073741824)";
  const char* begin = text.c_str();
  char* end = nullptr;
  if (text.empty() || !(std::isdigit(static_cast<unsigned char>(text[0])) || text[0] == '.')) throw InputError(problem);
  const double number = std::strtod(begin, &end);
  std::string suffix(end);
  for (char& c : suffix) c = char(std::tolower(static_cast<unsigned char>(c)));
  double scale = 1;
  if (!suffix.empty() && std::string("kmgt").find(suffix[0]) != std::string::npos) {
    scale = std::pow(1024.0, double(std::string("kmgt").find(suffix[0]) + 1));
    suffix.erase(0, 1);
    if (suffix == "ib" || suffix == "b") suffix.clear();
  } else if (suffix == "b") {
    suffix.clear();
  }
  const double bytes = number * scale;
  // The range check comes before the conversion: a double above 2^64 has no uint64_t value.
  if (!suffix.empty() || !std::isfinite(bytes) || bytes < 1 || bytes > 9.2e18) throw InputError(problem);
  return uint64_t(bytes);
}

}  // namespace dqskin
