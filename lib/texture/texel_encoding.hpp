// How a texture stores one channel value (internal to the texture writers and their decode-back check):
// as float32 or half in an EXR, or as 16- or 8-bit unsigned integers in a PNG after remapping a recorded
// range [lo, hi] to [0, 1]. Also the octahedral encoding of unit normals into two such channels. Every
// encoder has its exact decoder, the one the runtime's shader applies, so the written texels can be read
// back and compared with what was deformed.
#pragma once

#include "dqskin/dual_quat.hpp"

#include <cstdint>
#include <string>

namespace dqskin::texture {

enum class TexelType { kFloat32, kHalf, kUnorm16, kUnorm8 };

// "float", "half", "png16", "png8".
bool parse_texel_type(const std::string& text, TexelType& type);
const char* to_string(TexelType type);
bool is_png(TexelType type);
// Bytes of one channel as stored (before compression).
unsigned channel_bytes(TexelType type);

// The largest value a unorm channel holds: 65535 or 255 (0 for float types).
uint32_t unorm_max(TexelType type);

// Remaps x from [lo, hi] to the integer nearest to (x − lo) / (hi − lo) · max (round half up, so that the
// result never depends on the rounding mode). Requires lo ≤ x ≤ hi (the caller checked: clipping is an
// error, never silent); lo == hi stores 0.
uint32_t encode_unorm(double x, double lo, double hi, uint32_t max);
// The shader's inverse: lo + q / max · (hi − lo), in float as a GPU computes it.
float decode_unorm(uint32_t q, float lo, float hi, uint32_t max);

// x rounded to the nearest half-precision value (ties to even, as OpenEXR converts). Returns false when x
// is not finite or its magnitude rounds past 65504, the largest half (a stored infinity is an error).
bool to_half(float x, float& rounded);
// Half's spacing at |x|: the largest error of rounding x to half is half of it.
double half_ulp(double x);

// Octahedral encoding of a unit vector (Meyer et al., "On Floating-Point Normal Vectors", 2010, §3.3;
// Cigolle et al., "Survey of Efficient Representations for Independent Unit Vectors", JCGT 2014, §3.1):
// the sphere is projected onto the octahedron |x| + |y| + |z| = 1 and its lower half folded over the
// upper, giving (u, v) in [−1, 1]². `n` need not be exactly unit; zero maps to (0, 0).
glm::dvec2 octahedral_encode(const glm::dvec3& n);
// The inverse, normalized (the shader's decode); (u, v) in [−1, 1]².
glm::dvec3 octahedral_decode(const glm::dvec2& uv);

}  // namespace dqskin::texture
