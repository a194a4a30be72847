// shown_number and svg_number (report_numbers.hpp): the page's one rule for writing numbers.
#include "report_numbers.hpp"

#include <charconv>
#include <cmath>
#include <cstdint>

namespace dqskin::report_detail {
namespace {

std::string chars(double value, std::chars_format format, int precision) {
  char buffer[400];  // fixed notation of values below 1e15 with at most 6 decimals, or scientific
  const auto end = std::to_chars(buffer, buffer + sizeof buffer, value, format, precision).ptr;
  return std::string(buffer, end);
}

// "1.23e-05" -> "1.23e-5", "4.00e+15" -> "4.00e15": the exponent as JavaScript's toExponential writes it.
std::string bare_exponent(std::string text) {
  const size_t e = text.find('e');
  if (e == std::string::npos) return text;
  std::string exponent = text.substr(e + 1);
  std::string sign;
  if (!exponent.empty() && (exponent[0] == '+' || exponent[0] == '-')) {
    if (exponent[0] == '-') sign = "-";
    exponent.erase(0, 1);
  }
  const size_t digit = exponent.find_first_not_of('0');
  exponent = digit == std::string::npos ? "0" : exponent.substr(digit);
  return text.substr(0, e + 1) + sign + exponent;
}

}  // namespace

std::string shown_number(double value) {
  if (!std::isfinite(value)) return "\xE2\x80\x93";  // never in a report (the contract says null), but not a crash
  const double magnitude = std::fabs(value);
  if (magnitude < 1e15 && value == std::trunc(value)) {
    char buffer[32];
    const auto end = std::to_chars(buffer, buffer + sizeof buffer, int64_t(value)).ptr;
    return std::string(buffer, end);
  }
  if (magnitude < 1e-4 || magnitude >= 1e15) return bare_exponent(chars(value, std::chars_format::scientific, 2));
  int decimals = 0;
  if (magnitude < 100) decimals = 1;
  if (magnitude < 10) decimals = 2;
  if (magnitude < 1) decimals = 3;
  if (magnitude < 0.1) decimals = 4;
  if (magnitude < 0.01) decimals = 5;
  if (magnitude < 0.001) decimals = 6;
  return chars(value, std::chars_format::fixed, decimals);
}

std::string svg_number(double value) {
  std::string text = chars(value, std::chars_format::fixed, 1);
  if (text.size() >= 2 && text.compare(text.size() - 2, 2, ".0") == 0) text.resize(text.size() - 2);
  if (text == "-0") text = "0";
  return text;
}

}  // namespace dqskin::report_detail
