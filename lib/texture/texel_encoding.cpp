#include "texel_encoding.hpp"

#include <Imath/half.h>

#include <algorithm>
#include <cassert>
#include <cmath>

namespace dqskin::texture {

bool parse_texel_type(const std::string& text, TexelType& type) {
  if (text == "float") type = TexelType::kFloat32;
  else if (text == "half") type = TexelType::kHalf;
  else if (text == "png16") type = TexelType::kUnorm16;
  else if (text == "png8") type = TexelType::kUnorm8;
  else return false;
  return true;
}

const char* to_string(TexelType type) {
  switch (type) {
    case TexelType::kFloat32: return "float";
    case TexelType::kHalf: return "half";
    case TexelType::kUnorm16: return "png16";
    case TexelType::kUnorm8: return "png8";
  }
  return "?";
}

bool is_png(TexelType type) { return type == TexelType::kUnorm16 || type == TexelType::kUnorm8; }

unsigned channel_bytes(TexelType type) {
  switch (type) {
    case TexelType::kFloat32: return 4;
    case TexelType::kHalf:
    case TexelType::kUnorm16: return 2;
    case TexelType::kUnorm8: return 1;
  }
  return 0;
}

uint32_t unorm_max(TexelType type) {
  return type == TexelType::kUnorm16 ? 65535u : type == TexelType::kUnorm8 ? 255u : 0u;
}

uint32_t encode_unorm(double x, double lo, double hi, uint32_t max) {
  assert(lo <= x && x <= hi);
  if (!(hi > lo)) return 0;
  const double q = std::floor((x - lo) / (hi - lo) * max + 0.5);
  return uint32_t(std::clamp(q, 0.0, double(max)));
}

float decode_unorm(uint32_t q, float lo, float hi, uint32_t max) {
  return lo + float(q) / float(max) * (hi - lo);
}

bool to_half(float x, float& rounded) {
  if (!std::isfinite(x)) return false;
  const Imath::half h(x);  // round to nearest, ties to even; overflow becomes infinity
  rounded = float(h);
  return std::isfinite(rounded);
}

double half_ulp(double x) {
  // Normal halves have 10 fraction bits: spacing 2^(e − 10) in [2^e, 2^(e+1)); subnormals 2^−24.
  const double a = std::abs(x);
  if (a < std::ldexp(1.0, -14)) return std::ldexp(1.0, -24);
  return std::ldexp(1.0, std::ilogb(a) - 10);
}

glm::dvec2 octahedral_encode(const glm::dvec3& n) {
  const double l1 = std::abs(n.x) + std::abs(n.y) + std::abs(n.z);
  if (!(l1 > 0)) return {0, 0};
  glm::dvec2 p(n.x / l1, n.y / l1);
  if (n.z < 0) {  // fold the lower half over the diagonals
    const double sx = p.x >= 0 ? 1.0 : -1.0, sy = p.y >= 0 ? 1.0 : -1.0;
    p = glm::dvec2((1 - std::abs(p.y)) * sx, (1 - std::abs(p.x)) * sy);
  }
  return p;
}

glm::dvec3 octahedral_decode(const glm::dvec2& uv) {
  glm::dvec3 n(uv.x, uv.y, 1 - std::abs(uv.x) - std::abs(uv.y));
  if (n.z < 0) {
    const double sx = n.x >= 0 ? 1.0 : -1.0, sy = n.y >= 0 ? 1.0 : -1.0;
    const double x = (1 - std::abs(n.y)) * sx, y = (1 - std::abs(n.x)) * sy;
    n.x = x;
    n.y = y;
  }
  return glm::normalize(n);
}

}  // namespace dqskin::texture
