#include "vat_codec.hpp"

#include "dqskin/error.hpp"

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>

#include <algorithm>
#include <cassert>
#include <cmath>

namespace dqskin::texture {

namespace {

bool finite(const glm::dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// Houdini's packed normal (Labs VAT 3.0, textures/pack_normals): the normal in Unreal's axis order
// (x, z, y) projected by the spheremap transform f = √(8 n.z + 8), (px, py) = n.xy / f + ½, then stored as
// (⌊px·31⌋·32 + py·31) / 1023 (py is not floored). The exact downward normal has no projection: it is
// stored where the transform tends to, the edge of the disc.
double houdini_pack_normal(const glm::dvec3& n) {
  const glm::dvec3 u(n.x, n.z, n.y);
  const double g = 8 * u.z + 8;
  double px = 1, py = 0.5;
  if (g > 1e-12) {
    const double f = std::sqrt(g);
    px = std::clamp(u.x / f + 0.5, 0.0, 1.0);
    py = std::clamp(u.y / f + 0.5, 0.0, 1.0);
  }
  return (std::floor(px * 31) * 32 + py * 31) / 1023;
}

// The Unity VAT 3 shader's decode of that code, in float: a = A·1024, x = ⌊a/32⌋/31.5,
// y = (a − ⌊a/32⌋·32)/31.5, v = 4 (x, y) − 2, d = v·v, n = (v √(1 − d/4), 1 − d/2) in (x, z, y) order.
// (Unity then negates x for its left-handed axes; here the result stays in Houdini's, glTF's, axes.)
glm::vec3 houdini_unpack_normal(float code) {
  const float a = code * 1024.0f;
  const float hi = std::floor(a / 32.0f);
  const float x = hi / 31.5f, y = (a - hi * 32.0f) / 31.5f;
  const glm::vec2 v = glm::vec2(x, y) * 4.0f - 2.0f;
  const float d = glm::dot(v, v);
  const glm::vec2 xy = v * std::sqrt(std::max(0.0f, 1.0f - d / 4.0f));
  const float z = 1.0f - d / 2.0f;
  const glm::vec3 n = glm::clamp(glm::vec3(xy.x, z, xy.y), -1.0f, 1.0f);
  const float l = glm::length(n);
  return l > 0 ? n / l : glm::vec3(0, 1, 0);
}

// Houdini's rotation texture: a unit quaternion q that turns +y into the normal and −x into the tangent
// (the Unity VAT 3 shader reads N = q·(0,1,0)·q*, T = q·(−1,0,0)·q*), with w ≥ 0. Without a tangent any
// perpendicular direction serves: the normal is what is checked.
glm::dquat houdini_rotation(const glm::dvec3& n, const glm::dvec3* tangent) {
  glm::dvec3 t;
  if (tangent) t = *tangent - n * glm::dot(*tangent, n);
  if (!tangent || glm::length(t) < 1e-6) t = glm::cross(n, std::abs(n.z) < 0.9 ? glm::dvec3(0, 0, 1) : glm::dvec3(1, 0, 0));
  t = glm::normalize(t);
  const glm::dvec3 x = -t, y = n, z = glm::cross(x, y);
  glm::dquat q = glm::quat_cast(glm::dmat3(x, y, z));
  if (q.w < 0) q = -q;
  return glm::normalize(q);
}

// rot(q, v) = v + 2 q.xyz × (q.xyz × v + q.w v), as the shader writes it.
glm::vec3 rotate(const glm::vec4& q, const glm::vec3& v) {
  const glm::vec3 u(q.x, q.y, q.z);
  return v + 2.0f * glm::cross(u, glm::cross(u, v) + q.w * v);
}

// Unit normal → [0, 1]³ as every profile that stores n·½ + ½ does.
glm::dvec3 half_biased(const glm::dvec3& n) { return n * 0.5 + 0.5; }

}  // namespace

glm::dvec3 to_profile_axes(VatProfile profile, const glm::dvec3& g) {
  return profile == VatProfile::kOpenVat ? glm::dvec3(g.x, -g.z, g.y) : g;
}

glm::dvec3 from_profile_axes(VatProfile profile, const glm::dvec3& s) {
  return profile == VatProfile::kOpenVat ? glm::dvec3(s.x, s.z, -s.y) : s;
}

void Box::add(const glm::dvec3& p) {
  lo = glm::min(lo, p);
  hi = glm::max(hi, p);
}

void Box::add(const Box& b) {
  if (b.empty()) return;
  add(b.lo);
  add(b.hi);
}

double Box::diagonal() const { return empty() ? 0 : glm::length(hi - lo); }

std::optional<TexelType> VatEncoding::normal_image_type() const {
  switch (layout.format.normals) {
    case NormalMode::kSeparate: return layout.format.type;
    case NormalMode::kOct8: return TexelType::kUnorm8;
    case NormalMode::kOct16: return TexelType::kUnorm16;
    case NormalMode::kNone:
    case NormalMode::kPacked: return std::nullopt;
  }
  return std::nullopt;
}

glm::dvec3 stored_position(const VatEncoding& e, size_t v, const glm::vec3& position) {
  glm::dvec3 p(position);
  if (e.stores_offsets()) p -= glm::dvec3(e.rest[3 * v], e.rest[3 * v + 1], e.rest[3 * v + 2]);
  return to_profile_axes(e.layout.format.profile, p);
}

int normal_channels(const VatEncoding& e) {
  const VatFormat& f = e.layout.format;
  if (f.profile == VatProfile::kHoudini) return 4;
  if (f.profile == VatProfile::kDqskin && f.normals == NormalMode::kSeparate && !is_png(f.type)) return 4;
  return 3;
}

void encode_vat_frame(const VatEncoding& e, const FrameView& frame, size_t f, TexelImage& positions,
                      TexelImage* normals, const std::string& what) {
  const VatLayout& l = e.layout;
  const VatFormat& fmt = l.format;
  const TexelType type = fmt.type;
  auto fail = [&](size_t v, const std::string& why) {
    throw InputError(what + ", frame " + std::to_string(f) + ", vertex " + std::to_string(v) + ": " + why);
  };
  // One channel value into `image`: remapped by [lo, hi] for the integer types (and for any type when
  // `remap_float`), rounded to half, or as is.
  auto store = [&](TexelImage& image, TexelType t, size_t x, size_t y, int c, double value, double lo, double hi,
                   bool remap_float, size_t v) {
    const uint32_t m = unorm_max(t);
    if (!std::isfinite(value)) fail(v, "the value to store is not finite");
    if (m) {
      if (value < lo || value > hi) {
        std::string why = "value " + std::to_string(value) + " lies outside the remap bounds [" + std::to_string(lo) +
                          ", " + std::to_string(hi) + "]";
        if (fmt.profile == VatProfile::kHoudini)
          why += " (Houdini's PNG encodings remap offsets by the clip's absolute bounds; use --encoding half or float)";
        fail(v, why);
      }
      image.set(x, y, c, float(encode_unorm(value, lo, hi, m)));
      return;
    }
    if (remap_float) value = hi > lo ? (value - lo) / (hi - lo) : 0.0;
    float stored = float(value);
    if (t == TexelType::kHalf && !to_half(stored, stored))
      fail(v, "value " + std::to_string(value) + " overflows half precision (largest 65504); use --encoding float");
    image.set(x, y, c, stored);
  };

  size_t v = 0;
  for (const PrimitiveView& p : frame.primitives) {
    for (size_t k = 0; k < p.vertices; ++k, ++v) {
      const glm::vec3 position(p.positions[3 * k], p.positions[3 * k + 1], p.positions[3 * k + 2]);
      const glm::dvec3 s = stored_position(e, v, position);
      if (!finite(s)) fail(v, "the position is not finite");
      const TexelAt at = l.position(v, f);
      const bool remap_float = e.remapped;
      for (int c = 0; c < 3; ++c) store(positions, type, at.x, at.y, c, s[c], e.bounds.lo[c], e.bounds.hi[c], remap_float, v);
      if (fmt.profile == VatProfile::kDqskin && !is_png(type)) positions.set(at.x, at.y, 3, 1.0f);  // w = 1

      if (fmt.normals == NormalMode::kNone) continue;
      glm::dvec3 n(0.0);
      if (!p.normals.empty()) n = glm::dvec3(p.normals[3 * k], p.normals[3 * k + 1], p.normals[3 * k + 2]);
      if (!finite(n)) fail(v, "the normal is not finite");
      const glm::dvec3 na = to_profile_axes(fmt.profile, n);
      if (fmt.profile == VatProfile::kHoudini) {
        const glm::dvec3 unit = glm::length(n) > 0 ? glm::normalize(n) : glm::dvec3(0, 1, 0);
        if (fmt.normals == NormalMode::kPacked) {
          store(positions, type, at.x, at.y, 3, houdini_pack_normal(unit), 0, 1, false, v);
          continue;
        }
        glm::dvec3 tangent;
        const bool has_tangent = !p.tangents.empty();
        if (has_tangent) tangent = glm::dvec3(p.tangents[4 * k], p.tangents[4 * k + 1], p.tangents[4 * k + 2]);
        const glm::dquat q = houdini_rotation(unit, has_tangent ? &tangent : nullptr);
        const double xyzw[4] = {q.x, q.y, q.z, q.w};
        for (int c = 0; c < 4; ++c) {
          const double value = is_png(type) ? xyzw[c] * 0.5 + 0.5 : xyzw[c];
          store(*normals, type, at.x, at.y, c, value, 0, 1, false, v);
        }
        continue;
      }
      if (fmt.normals == NormalMode::kOct8 || fmt.normals == NormalMode::kOct16) {
        const glm::dvec2 o = octahedral_encode(na) * 0.5 + 0.5;
        store(*normals, normals->type(), at.x, at.y, 0, o.x, 0, 1, false, v);
        store(*normals, normals->type(), at.x, at.y, 1, o.y, 0, 1, false, v);
        continue;
      }
      // dqskin float and half keep raw xyz (w = 0); every other case stores n·½ + ½.
      const bool raw = fmt.profile == VatProfile::kDqskin && !is_png(type);
      const glm::dvec3 value = raw ? na : half_biased(na);
      if (fmt.normals == NormalMode::kPacked) {  // openvat: the lower half of the position image
        const TexelAt nat = l.packed_normal(v, f);
        for (int c = 0; c < 3; ++c) store(positions, type, nat.x, nat.y, c, value[c], 0, 1, false, v);
        continue;
      }
      for (int c = 0; c < 3; ++c) store(*normals, type, at.x, at.y, c, value[c], 0, 1, false, v);
    }
  }
}

void decode_vat_frame(const VatEncoding& e, const TexelImage& positions, const TexelImage* normals, size_t f,
                      std::vector<float>& out_positions, std::vector<float>& out_normals) {
  const VatLayout& l = e.layout;
  const VatFormat& fmt = l.format;
  const size_t n = l.vertices;
  out_positions.resize(3 * n);
  out_normals.assign(fmt.normals == NormalMode::kNone ? 0 : 3 * n, 0.0f);
  // The shader's remap: lo + t (hi − lo), t the texel (float and half) or q / max (integers).
  auto channel = [&](const TexelImage& image, size_t x, size_t y, int c) {
    const uint32_t m = unorm_max(image.type());
    const float s = image.get(x, y, c);
    return m ? s / float(m) : s;
  };
  const glm::vec3 lo(e.bounds.lo), hi(e.bounds.hi);
  for (size_t v = 0; v < n; ++v) {
    const TexelAt at = l.position(v, f);
    glm::vec3 s(channel(positions, at.x, at.y, 0), channel(positions, at.x, at.y, 1), channel(positions, at.x, at.y, 2));
    if (e.remapped) s = lo + s * (hi - lo);
    glm::vec3 p = glm::vec3(from_profile_axes(fmt.profile, glm::dvec3(s)));
    if (e.stores_offsets()) p += glm::vec3(e.rest[3 * v], e.rest[3 * v + 1], e.rest[3 * v + 2]);
    for (int c = 0; c < 3; ++c) out_positions[3 * v + size_t(c)] = p[c];

    if (fmt.normals == NormalMode::kNone) continue;
    glm::vec3 nrm(0.0f);
    if (fmt.profile == VatProfile::kHoudini) {
      if (fmt.normals == NormalMode::kPacked) {
        nrm = houdini_unpack_normal(positions.get(at.x, at.y, 3));
      } else {
        glm::vec4 q(channel(*normals, at.x, at.y, 0), channel(*normals, at.x, at.y, 1),
                    channel(*normals, at.x, at.y, 2), channel(*normals, at.x, at.y, 3));
        if (is_png(normals->type())) q = q * 2.0f - 1.0f;
        nrm = rotate(q, glm::vec3(0, 1, 0));
      }
    } else if (fmt.normals == NormalMode::kOct8 || fmt.normals == NormalMode::kOct16) {
      const glm::dvec2 o(channel(*normals, at.x, at.y, 0), channel(*normals, at.x, at.y, 1));
      nrm = glm::vec3(from_profile_axes(fmt.profile, octahedral_decode(o * 2.0 - 1.0)));
    } else {
      const TexelImage& image = fmt.normals == NormalMode::kPacked ? positions : *normals;
      const TexelAt nat = fmt.normals == NormalMode::kPacked ? l.packed_normal(v, f) : at;
      glm::vec3 s3(channel(image, nat.x, nat.y, 0), channel(image, nat.x, nat.y, 1), channel(image, nat.x, nat.y, 2));
      const bool raw = fmt.profile == VatProfile::kDqskin && !is_png(fmt.type);
      if (!raw) s3 = s3 * 2.0f - 1.0f;
      nrm = glm::vec3(from_profile_axes(fmt.profile, glm::dvec3(s3)));
    }
    const float len = glm::length(nrm);
    if (len > 0) nrm /= len;
    for (int c = 0; c < 3; ++c) out_normals[3 * v + size_t(c)] = nrm[c];
  }
}

double position_encoding_bound(const VatEncoding& e) {
  const TexelType type = e.layout.format.type;
  double squares = 0, largest = 0;
  for (int c = 0; c < 3; ++c) {
    const double range = e.remapped ? e.bounds.hi[c] - e.bounds.lo[c] : 0.0;
    const double magnitude = e.stored.empty() ? 0.0 : std::max(std::abs(e.stored.lo[c]), std::abs(e.stored.hi[c]));
    double b = 0;
    if (const uint32_t m = unorm_max(type)) b = range / (2.0 * m);
    else if (type == TexelType::kHalf) b = e.remapped ? range * half_ulp(0.999) / 2 : half_ulp(magnitude) / 2;
    squares += b * b;
    largest = std::max({largest, magnitude, std::abs(e.bounds.empty() ? 0.0 : e.bounds.lo[c]),
                        std::abs(e.bounds.empty() ? 0.0 : e.bounds.hi[c])});
  }
  // The decode's float arithmetic (a remap and the rest added): a few roundings of values as large as
  // the positions, on each axis.
  for (float r : e.rest) largest = std::max(largest, std::abs(double(r)));
  return std::sqrt(squares) + 8 * std::ldexp(largest, -24) * std::sqrt(3.0);
}

}  // namespace dqskin::texture
