// Test support: decoding base64 (RFC 4648 section 4, padded), to read back what the library encoded
// (base/base64.hpp) from data URIs. Returns false on anything that is not canonical padded base64.
#pragma once

#include <cstdint>
#include <string_view>
#include <vector>

namespace dqskin::testing_support {

inline bool base64_decode(std::string_view text, std::vector<uint8_t>& bytes) {
  bytes.clear();
  if (text.size() % 4 != 0) return false;
  const auto value = [](char c) -> int {
    if (c >= 'A' && c <= 'Z') return c - 'A';
    if (c >= 'a' && c <= 'z') return c - 'a' + 26;
    if (c >= '0' && c <= '9') return c - '0' + 52;
    if (c == '+') return 62;
    if (c == '/') return 63;
    return -1;
  };
  for (size_t i = 0; i < text.size(); i += 4) {
    const bool last = i + 4 == text.size();
    const int pad = last ? (text[i + 3] == '=') + (text[i + 2] == '=') : 0;
    if (last && pad == 1 && text[i + 2] == '=') return false;
    uint32_t group = 0;
    for (int k = 0; k < 4; ++k) {
      const int v = k >= 4 - pad ? 0 : value(text[i + size_t(k)]);
      if (v < 0) return false;
      group = group << 6 | uint32_t(v);
    }
    bytes.push_back(uint8_t(group >> 16));
    if (pad < 2) bytes.push_back(uint8_t(group >> 8 & 0xFF));
    if (pad < 1) bytes.push_back(uint8_t(group & 0xFF));
  }
  return true;
}

}  // namespace dqskin::testing_support
