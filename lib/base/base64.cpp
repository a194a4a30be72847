#include "base64.hpp"

namespace dqskin::io {

std::string base64(std::span<const uint8_t> bytes) {
  static constexpr char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";  // RFC 4648 table 1
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  const size_t n = bytes.size();
  // Each group of 3 bytes is 24 bits, written as 4 characters of 6 bits; a last group of 1 or 2 bytes is
  // filled with zero bits and its missing characters are '=' (section 4, cases 2 and 3).
  for (size_t i = 0; i < n; i += 3) {
    const uint32_t group = uint32_t(bytes[i]) << 16 | (i + 1 < n ? uint32_t(bytes[i + 1]) << 8 : 0u) |
                           (i + 2 < n ? uint32_t(bytes[i + 2]) : 0u);
    out += kAlphabet[group >> 18 & 63];
    out += kAlphabet[group >> 12 & 63];
    out += i + 1 < n ? kAlphabet[group >> 6 & 63] : '=';
    out += i + 2 < n ? kAlphabet[group & 63] : '=';
  }
  return out;
}

}  // namespace dqskin::io
