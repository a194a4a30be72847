// 8-bit codes from linear values: the one encoder of every 8-bit image dqskin writes (rendered PNGs,
// contact sheets, GIFs, diff heat maps). Done here rather than by an sRGB framebuffer, so that the bytes
// do not depend on a driver's conversion.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace dqskin::io {

// The IEC 61966-2-1 (sRGB) transfer function, linear [0, 1] (clamped) to an encoded value in [0, 1].
inline double srgb_encode(double linear) {
  const double c = std::clamp(linear, 0.0, 1.0);
  return c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055;
}

// The same to an 8-bit code, rounded to nearest.
inline uint8_t srgb8(float linear) { return uint8_t(std::lround(srgb_encode(double(linear)) * 255.0)); }

// A linear quantity stored linearly (alpha): [0, 1] (clamped) to 0-255, rounded to nearest.
inline uint8_t unorm8(float value) { return uint8_t(std::lround(std::clamp(double(value), 0.0, 1.0) * 255.0)); }

}  // namespace dqskin::io
