// One printable line from any bytes (include/dqskin/error.hpp).
#include "dqskin/error.hpp"
#include "utf8.hpp"

#include <cstdint>
#include <cstdio>

namespace dqskin {
namespace {

void append_escape(std::string& out, const char* format, unsigned value) {
  char text[16];  // "\\u" and up to 8 hex digits
  std::snprintf(text, sizeof text, format, value);
  out += text;
}

// Code points a terminal acts on instead of showing: C1 controls (U+009B is a CSI on some terminals),
// line and paragraph separators, and the bidirectional controls that reorder the rest of a line.
bool moves_text(uint32_t code) {
  return (code >= 0x80 && code <= 0x9F) || code == 0x2028 || code == 0x2029 || (code >= 0x200E && code <= 0x200F) ||
         (code >= 0x202A && code <= 0x202E) || (code >= 0x2066 && code <= 0x2069) || code == 0x061C;
}

}  // namespace

std::string printable(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (size_t i = 0; i < text.size();) {
    const uint8_t c = uint8_t(text[i]);
    if (c >= 0x20 && c < 0x7F) {
      out += char(c);
      ++i;
      continue;
    }
    switch (c) {
      case '\n': out += "\\n"; ++i; continue;
      case '\r': out += "\\r"; ++i; continue;
      case '\t': out += "\\t"; ++i; continue;
      default: break;
    }
    if (c < 0x80) {  // the other C0 controls and DEL
      append_escape(out, "\\x%02x", c);
      ++i;
      continue;
    }
    uint32_t code = 0;
    const size_t length = utf8_sequence(text, i, code);
    if (length == 0) {
      append_escape(out, "\\x%02x", c);
      ++i;
    } else if (moves_text(code)) {
      append_escape(out, "\\u%04x", code);
      i += length;
    } else {
      out.append(text.substr(i, length));
      i += length;
    }
  }
  return out;
}

}  // namespace dqskin
