// Decoding one UTF-8 sequence (internal to the library: printable() and the XML of diff reports).
#pragma once

#include <cstdint>
#include <string_view>

namespace dqskin {

// Length of the well-formed UTF-8 sequence of 2 to 4 bytes at text[i], or 0 (RFC 3629: no overlong
// forms, no surrogates, nothing above U+10FFFF); its code point in `code`. ASCII (< 0x80) is not a
// sequence here: callers handle it first.
inline size_t utf8_sequence(std::string_view text, size_t i, uint32_t& code) {
  const auto byte = [&](size_t k) { return uint8_t(text[k]); };
  const uint8_t lead = byte(i);
  size_t length = 0;
  uint32_t min = 0;
  if (lead >= 0xC2 && lead <= 0xDF) length = 2, code = lead & 0x1Fu, min = 0x80;
  else if (lead >= 0xE0 && lead <= 0xEF) length = 3, code = lead & 0x0Fu, min = 0x800;
  else if (lead >= 0xF0 && lead <= 0xF4) length = 4, code = lead & 0x07u, min = 0x10000;
  else return 0;
  if (i + length > text.size()) return 0;
  for (size_t k = 1; k < length; ++k) {
    if ((byte(i + k) & 0xC0) != 0x80) return 0;
    code = code << 6 | (byte(i + k) & 0x3Fu);
  }
  if (code < min || code > 0x10FFFF || (code >= 0xD800 && code <= 0xDFFF)) return 0;
  return length;
}

}  // namespace dqskin
