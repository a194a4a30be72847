#include "image_size.hpp"

#include <cstring>

namespace dqskin::gltf {
namespace {

uint32_t be16(const uint8_t* p) { return uint32_t(p[0]) << 8 | p[1]; }
uint32_t be32(const uint8_t* p) { return be16(p) << 16 | be16(p + 2); }
uint32_t le16(const uint8_t* p) { return uint32_t(p[1]) << 8 | p[0]; }
uint32_t le24(const uint8_t* p) { return uint32_t(p[2]) << 16 | le16(p); }

using Size = std::optional<std::pair<uint32_t, uint32_t>>;

// PNG (ISO/IEC 15948 §11.2.2): the signature, then IHDR's length and type, width and height.
Size png(std::span<const uint8_t> b) {
  if (b.size() < 24 || std::memcmp(b.data() + 12, "IHDR", 4) != 0) return {};
  return std::pair{be32(&b[16]), be32(&b[20])};
}

// JPEG (ITU T.81 §B.2): markers after SOI until a start-of-frame (C0-CF, except C4 DHT, C8 JPG, CC DAC),
// whose segment holds precision, height, width.
Size jpeg(std::span<const uint8_t> b) {
  size_t i = 2;
  while (i + 4 <= b.size()) {
    if (b[i] != 0xFF) return {};
    const uint8_t marker = b[i + 1];
    if (marker == 0xFF) {  // fill byte
      ++i;
      continue;
    }
    if (marker == 0xD8 || (marker >= 0xD0 && marker <= 0xD7) || marker == 0x01) {  // no length
      i += 2;
      continue;
    }
    const size_t length = be16(&b[i + 2]);
    if (marker >= 0xC0 && marker <= 0xCF && marker != 0xC4 && marker != 0xC8 && marker != 0xCC) {
      if (length < 7 || i + 9 > b.size()) return {};
      return std::pair{be16(&b[i + 7]), be16(&b[i + 5])};
    }
    if (length < 2) return {};
    i += 2 + length;
  }
  return {};
}

// WebP (RFC 9649): RIFF, then VP8X (canvas size - 1, 24 bits each), VP8L (14-bit sizes - 1 after the
// 0x2F signature) or VP8 (14-bit sizes after the 0x9D 0x01 0x2A start code).
Size webp(std::span<const uint8_t> b) {
  if (b.size() < 30) return {};
  const uint8_t* chunk = &b[12];
  if (std::memcmp(chunk, "VP8X", 4) == 0) return std::pair{le24(&b[24]) + 1, le24(&b[27]) + 1};
  if (std::memcmp(chunk, "VP8L", 4) == 0 && b[20] == 0x2F) {
    const uint32_t bits = uint32_t(b[21]) | uint32_t(b[22]) << 8 | uint32_t(b[23]) << 16 | uint32_t(b[24]) << 24;
    return std::pair{(bits & 0x3FFF) + 1, ((bits >> 14) & 0x3FFF) + 1};
  }
  if (std::memcmp(chunk, "VP8 ", 4) == 0 && b[23] == 0x9D && b[24] == 0x01 && b[25] == 0x2A)
    return std::pair{le16(&b[26]) & 0x3FFF, le16(&b[28]) & 0x3FFF};
  return {};
}

}  // namespace

Size declared_image_size(std::span<const uint8_t> b) {
  if (b.size() >= 8 && std::memcmp(b.data(), "\x89PNG\r\n\x1a\n", 8) == 0) return png(b);
  if (b.size() >= 3 && b[0] == 0xFF && b[1] == 0xD8 && b[2] == 0xFF) return jpeg(b);
  if (b.size() >= 12 && std::memcmp(b.data(), "RIFF", 4) == 0 && std::memcmp(b.data() + 8, "WEBP", 4) == 0) return webp(b);
  return {};
}

}  // namespace dqskin::gltf
