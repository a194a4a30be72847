#include "xml_escape.hpp"
#include "utf8.hpp"

#include <cstdint>

namespace dqskin::io {

std::string xml(const std::string& text, bool attribute) {
  std::string out;
  const auto* s = reinterpret_cast<const unsigned char*>(text.data());
  const size_t n = text.size();
  for (size_t i = 0; i < n;) {
    const unsigned char c = s[i];
    if (c < 0x80) {
      switch (c) {
        case '&': out += "&amp;"; break;
        case '<': out += "&lt;"; break;
        case '>': out += "&gt;"; break;
        case '"': out += attribute ? "&quot;" : "\""; break;
        case '\'': out += attribute ? "&apos;" : "'"; break;
        case '\n': out += attribute ? "&#10;" : "\n"; break;
        case '\r': out += "&#13;"; break;
        case '\t': out += attribute ? "&#9;" : "\t"; break;
        default: out += c < 0x20 || c == 0x7f ? "\xEF\xBF\xBD" : std::string(1, char(c));
      }
      ++i;
      continue;
    }
    uint32_t code = 0;
    const size_t length = utf8_sequence(text, i, code);
    const bool valid = length > 0 && code != 0xFFFE && code != 0xFFFF;  // XML 1.0 Char excludes both
    if (valid) {
      out.append(text, i, length);
      i += length;
    } else {
      out += "\xEF\xBF\xBD";
      ++i;
    }
  }
  return out;
}

}  // namespace dqskin::io
