// The body of the fast CPU kernel (fast_kernel.hpp), included once per instruction set by
// fast_kernel_<isa>.cpp with DQSKIN_KERNEL_NAMESPACE set. Everything here has internal linkage or lives
// in that namespace, and only compiler builtins are called, so no function compiled for a wider
// instruction set can be picked by the linker for code that runs on a narrower one.
//
// The arithmetic is glsl/skin.comp's, lane by lane (GCC vector extensions: one operator, kLanes vertices):
// morph targets first (glTF 2.0 §3.7.2.2), then lbs, or dqs as DLB (Kavan et al. 2008, §4) with every
// influence flipped into the hemisphere of the largest one, and the two-phase rule for scale
// (docs/DESIGN.md §3.6): v' = DLB(rigid) applied to (Σ w S) v.
#include "fast_kernel.hpp"

#if defined(__AVX2__)
#include <immintrin.h>
#endif

#ifndef DQSKIN_KERNEL_NAMESPACE
#error "define DQSKIN_KERNEL_NAMESPACE before including fast_kernel_body.hpp"
#endif

namespace dqskin::deform::DQSKIN_KERNEL_NAMESPACE {
namespace {

// The helpers below take and return whole vectors; a call that is not inlined passes them through memory.
#define ALWAYS_INLINE inline __attribute__((always_inline))

typedef float V __attribute__((vector_size(kLanes * sizeof(float))));

struct V3 {
  V x, y, z;
};

ALWAYS_INLINE V splat(float x) { return V{} + x; }
ALWAYS_INLINE V load(const float* p) {
  V v;
  __builtin_memcpy(&v, p, sizeof v);
  return v;
}
ALWAYS_INLINE V3 load3(const float* const* arrays, size_t v) { return {load(arrays[0] + v), load(arrays[1] + v), load(arrays[2] + v)}; }

static_assert(kLanes == 8 && kPaletteStride == 16, "fetch8 transposes 8 lanes × 8 floats, half a palette entry");

// Eight consecutive palette floats of each lane's joint, from `offset` (0 or 8), transposed so that out[e]
// holds float e of every lane. With AVX2 that is eight 32-byte loads and an 8×8 transpose in registers:
// about three times faster than eight gathers on the CPUs measured (docs/PERFORMANCE.md).
ALWAYS_INLINE void fetch8(const float* palette, const int32_t* joints, size_t offset, V (&out)[8]) {
#if defined(__AVX2__)
  __m256 r[8];
  for (size_t l = 0; l < 8; ++l) r[l] = _mm256_loadu_ps(palette + size_t(joints[l]) * kPaletteStride + offset);
  __m256 t[8], s[8];
  for (size_t h = 0; h < 8; h += 2) {
    t[h] = _mm256_unpacklo_ps(r[h], r[h + 1]);      // r_h[0] r_h+1[0] r_h[1] r_h+1[1] | the same for 4, 5
    t[h + 1] = _mm256_unpackhi_ps(r[h], r[h + 1]);  // floats 2, 3 | 6, 7
  }
  for (size_t h = 0; h < 8; h += 4) {
    s[h] = _mm256_shuffle_ps(t[h], t[h + 2], 0x44);      // float 0 of lanes h … h+3 | float 4
    s[h + 1] = _mm256_shuffle_ps(t[h], t[h + 2], 0xEE);  // float 1 | 5
    s[h + 2] = _mm256_shuffle_ps(t[h + 1], t[h + 3], 0x44);  // float 2 | 6
    s[h + 3] = _mm256_shuffle_ps(t[h + 1], t[h + 3], 0xEE);  // float 3 | 7
  }
  for (size_t e = 0; e < 4; ++e) {
    out[e] = V(_mm256_permute2f128_ps(s[e], s[e + 4], 0x20));
    out[e + 4] = V(_mm256_permute2f128_ps(s[e], s[e + 4], 0x31));
  }
#else
  for (size_t l = 0; l < 8; ++l)
    for (size_t e = 0; e < 8; ++e) out[e][l] = palette[size_t(joints[l]) * kPaletteStride + offset + e];
#endif
}

ALWAYS_INLINE V sqrt_lanes(V x) {
#if defined(__AVX__)
  return V(_mm256_sqrt_ps(__m256(x)));
#else
  V r;
  for (size_t l = 0; l < kLanes; ++l) r[l] = __builtin_sqrtf(x[l]);
  return r;
#endif
}

ALWAYS_INLINE V3 operator+(V3 a, V3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
ALWAYS_INLINE V3 operator*(V s, V3 a) { return {s * a.x, s * a.y, s * a.z}; }
ALWAYS_INLINE V dot(V3 a, V3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
ALWAYS_INLINE V3 cross(V3 a, V3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }

// A 3×3 matrix by columns.
struct M3 {
  V3 c0, c1, c2;
};
ALWAYS_INLINE V3 operator*(const M3& m, V3 v) { return v.x * m.c0 + v.y * m.c1 + v.z * m.c2; }
// det(A) A⁻ᵀ by columns: the normal transform that needs no inverse (as skin.comp and the reference).
ALWAYS_INLINE M3 cofactor(const M3& a) { return {cross(a.c1, a.c2), cross(a.c2, a.c0), cross(a.c0, a.c1)}; }

// q v q* for a unit quaternion (vector part u, scalar w): v + 2 u × (u × v + w v).
ALWAYS_INLINE V3 rotate(V3 u, V w, V3 v) { return v + splat(2) * cross(u, cross(u, v) + w * v); }

// v / |v|, or v itself when it has no length (as skin.comp).
ALWAYS_INLINE V3 unit_or_same(V3 v) {
  const V length = sqrt_lanes(dot(v, v));
  const V inverse = length > V{} ? splat(1) / length : splat(1);
  return inverse * v;
}

// Writes the valid lanes of a block as AoS: `components` (3 or 4) floats per vertex.
template <size_t components>
ALWAYS_INLINE void store(float* out, size_t first, size_t count, const V (&c)[components]) {
  float block[kLanes * components];
  for (size_t l = 0; l < kLanes; ++l)
    for (size_t k = 0; k < components; ++k) block[l * components + k] = c[k][l];
  __builtin_memcpy(out + first * components, block, count * components * sizeof(float));
}

template <KernelMode mode>
void deform_blocks(const KernelPrimitive& prim, const KernelFrame& frame, size_t first, size_t last) {
  const size_t padded = prim.blocks * kLanes;
  const bool normals = prim.normal[0] != nullptr, tangents = prim.tangent[0] != nullptr;
  for (size_t b = first; b < last; ++b) {
    const size_t v0 = b * kLanes;
    V3 p = load3(prim.position, v0);
    V3 n{}, t{};
    if (normals) n = load3(prim.normal, v0);
    if (tangents) t = load3(prim.tangent, v0);

    // Morph targets before skinning; a target at weight 0 is skipped for every lane at once.
    for (size_t m = 0; m < prim.targets; ++m) {
      const float w = frame.morph_weights[m];
      if (w == 0) continue;
      const float* const* parts = prim.morph + m * 3;
      const V wv = splat(w);
      auto add = [&](V3& x, const float* part) {
        if (part) x = x + wv * V3{load(part + v0), load(part + padded + v0), load(part + 2 * padded + v0)};
      };
      add(p, parts[0]);
      if (normals) add(n, parts[1]);
      if (tangents) add(t, parts[2]);
    }

    if constexpr (mode == KernelMode::kLbs) {
      // Σ w · [A | t] over the influences, then A p + t, cof(A) n, A t.
      V a[12] = {};
      for (size_t k = 0; k < prim.influences; ++k) {
        const int32_t* joints = prim.joint + k * padded + v0;
        const V w = load(prim.weight + k * padded + v0);
        V low[8], high[8];
        fetch8(frame.palette, joints, 0, low);
        fetch8(frame.palette, joints, 8, high);
        for (size_t e = 0; e < 8; ++e) a[e] += w * low[e];
        for (size_t e = 0; e < 4; ++e) a[8 + e] += w * high[e];
      }
      const M3 m{{a[0], a[1], a[2]}, {a[3], a[4], a[5]}, {a[6], a[7], a[8]}};
      p = m * p + V3{a[9], a[10], a[11]};
      if (normals) n = cofactor(m) * n;
      if (tangents) t = m * t;
    } else {
      // DLB: influence 0 is the pivot (the largest weight); the others join its hemisphere.
      const V w0 = load(prim.weight + v0);
      V pivot[8];  // real, dual
      fetch8(frame.palette, prim.joint + v0, 0, pivot);
      V real[4], dual[4];
      for (size_t e = 0; e < 4; ++e) {
        real[e] = w0 * pivot[e];
        dual[e] = w0 * pivot[4 + e];
      }
      V s[6] = {};
      if constexpr (mode == KernelMode::kDqsScale) {
        V scale0[8];
        fetch8(frame.palette, prim.joint + v0, 8, scale0);
        for (size_t e = 0; e < 6; ++e) s[e] = w0 * scale0[e];
      }
      for (size_t k = 1; k < prim.influences; ++k) {
        const int32_t* joints = prim.joint + k * padded + v0;
        const V w = load(prim.weight + k * padded + v0);
        V q[8];
        fetch8(frame.palette, joints, 0, q);
        const V side = q[0] * pivot[0] + q[1] * pivot[1] + q[2] * pivot[2] + q[3] * pivot[3];
        const V signed_w = side < V{} ? -w : w;
        for (size_t e = 0; e < 4; ++e) {
          real[e] += signed_w * q[e];
          dual[e] += signed_w * q[4 + e];
        }
        if constexpr (mode == KernelMode::kDqsScale) {
          V scale[8];
          fetch8(frame.palette, joints, 8, scale);
          for (size_t e = 0; e < 6; ++e) s[e] += w * scale[e];
        }
      }
      // Normalize by |real|; the part of dual along real moves no point, so it needs no projection.
      const V inverse = splat(1) / sqrt_lanes(real[0] * real[0] + real[1] * real[1] + real[2] * real[2] + real[3] * real[3]);
      const V3 u{real[0] * inverse, real[1] * inverse, real[2] * inverse};
      const V w = real[3] * inverse;
      const V3 d{dual[0] * inverse, dual[1] * inverse, dual[2] * inverse};
      const V dw = dual[3] * inverse;
      const V3 translation = splat(2) * (w * d + (-dw) * u + cross(u, d));
      if constexpr (mode == KernelMode::kDqsScale) {
        const M3 scale{{s[0], s[1], s[2]}, {s[1], s[3], s[4]}, {s[2], s[4], s[5]}};  // symmetric
        p = scale * p;
        if (normals) n = cofactor(scale) * n;
        if (tangents) t = scale * t;
      }
      p = rotate(u, w, p) + translation;
      if (normals) n = rotate(u, w, n);
      if (tangents) t = rotate(u, w, t);
    }

    const size_t count = v0 + kLanes <= frame.vertices ? kLanes : frame.vertices - v0;
    store<3>(frame.positions, v0, count, {p.x, p.y, p.z});
    if (normals) {
      n = unit_or_same(n);
      store<3>(frame.normals, v0, count, {n.x, n.y, n.z});
    }
    if (tangents) {
      t = unit_or_same(t);
      store<4>(frame.tangents, v0, count, {t.x, t.y, t.z, load(prim.tangent[3] + v0)});
    }
  }
}

#undef ALWAYS_INLINE

}  // namespace

KernelFunction kernel_function(KernelMode mode) {
  switch (mode) {
    case KernelMode::kLbs: return deform_blocks<KernelMode::kLbs>;
    case KernelMode::kDqs: return deform_blocks<KernelMode::kDqs>;
    case KernelMode::kDqsScale: break;
  }
  return deform_blocks<KernelMode::kDqsScale>;
}

}  // namespace dqskin::deform::DQSKIN_KERNEL_NAMESPACE
