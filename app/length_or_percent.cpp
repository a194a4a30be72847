// A length flag that is a length in scene units or a percentage of a bounding-box diagonal (bake's
// --max-error, report's --tolerance), read one way for both (commands.hpp LengthOrPercent).
#include "commands.hpp"

#include "dqskin/error.hpp"

#include <cmath>
#include <exception>

namespace dqskin::cli {

LengthOrPercent parse_length_or_percent(const std::string& text, bool allow_zero, const std::string& problem) {
  const bool relative = !text.empty() && text.back() == '%';
  const std::string number = relative ? text.substr(0, text.size() - 1) : text;
  size_t used = 0;
  double value = -1;
  try {
    value = std::stod(number, &used);
  } catch (const std::exception&) {
  }
  const bool in_range = allow_zero ? value >= 0 : value > 0;
  if (number.empty() || used != number.size() || !in_range || !std::isfinite(value)) throw InputError(problem);
  return {relative ? value / 100 : value, relative};
}

}  // namespace dqskin::cli
