// Skinning compute shader: one invocation per (vertex, frame). Reads the BoneTexture of docs/DESIGN.md §4.1
// (RGBA32F, row = frame, T texels per joint: real, dual [, the three rows of S]) with texelFetch and writes
// the deformed positions, normals and tangents of every frame of the batch.
//
// Compiled once per variant; the host prepends "#version 430" and these defines:
//   MODE_LBS | MODE_DQS    blend mode (DIB runs on the CPU reference only)
//   TEXELS                 T, texels per joint (2 rigid, 5 with scale/shear)
//   INFLUENCES             per vertex: 4 per JOINTS_n/WEIGHTS_n set, up to 32 (every set the file has)
//   HAS_NORMALS, HAS_TANGENTS, MORPH_TARGETS (count, 0 for none)
// Kavan et al., "Geometric Skinning with Approximate Dual Quaternion Blending" (2008): DLB (§4) with the
// antipodality pivot of docs/DESIGN.md §3.5, and two-phase skinning for scale: v' = DLB(rigid) applied to (Σ w S) v.

layout(local_size_x = 64, local_size_y = 1, local_size_z = 1) in;

layout(std430, binding = 0) readonly buffer RestPositions { float rest_position[]; };
layout(std430, binding = 1) readonly buffer RestNormals { float rest_normal[]; };
layout(std430, binding = 2) readonly buffer RestTangents { vec4 rest_tangent[]; };
// Per vertex: INFLUENCES/2 uints of two 16-bit joint indices, then INFLUENCES float weights.
layout(std430, binding = 3) readonly buffer Influences { uint influence[]; };
// Morph targets: [target][vertex] position offsets, then normal offsets, then tangent offsets (3 floats).
layout(std430, binding = 4) readonly buffer MorphOffsets { float morph_offset[]; };
// Morph weights: [frame of the batch][target].
layout(std430, binding = 5) readonly buffer MorphWeights { float morph_weight[]; };
layout(std430, binding = 6) writeonly buffer OutPositions { float out_position[]; };
layout(std430, binding = 7) writeonly buffer OutNormals { float out_normal[]; };
layout(std430, binding = 8) writeonly buffer OutTangents { vec4 out_tangent[]; };

uniform sampler2D bones;
uniform uint vertex_count;
uniform int first_row;  // bone texture row of the batch's frame 0

vec3 load3(uint i) { return vec3(rest_position[3u * i], rest_position[3u * i + 1u], rest_position[3u * i + 2u]); }

vec3 quat_rotate(vec4 q, vec3 v) { return v + 2.0 * cross(q.xyz, cross(q.xyz, v) + q.w * v); }

// det(A) A^-T by columns: the normal transform that needs no inverse (as the CPU reference).
mat3 cofactor(mat3 a) { return mat3(cross(a[1], a[2]), cross(a[2], a[0]), cross(a[0], a[1])); }

vec4 bone(int joint, int k, int row) { return texelFetch(bones, ivec2(TEXELS * joint + k, row), 0); }

mat3 bone_scale(int joint, int row) {
#if TEXELS == 5
  // Rows of the symmetric S, so they are also its columns.
  return mat3(bone(joint, 2, row).xyz, bone(joint, 3, row).xyz, bone(joint, 4, row).xyz);
#else
  return mat3(1.0);
#endif
}

void main() {
  const uint v = gl_GlobalInvocationID.x;
  const uint f = gl_GlobalInvocationID.y;
  if (v >= vertex_count) return;
  const int row = first_row + int(f);

  vec3 p = load3(v);
#ifdef HAS_NORMALS
  vec3 n = vec3(rest_normal[3u * v], rest_normal[3u * v + 1u], rest_normal[3u * v + 2u]);
#endif
#ifdef HAS_TANGENTS
  vec4 tangent = rest_tangent[v];
  vec3 t = tangent.xyz;
#endif

#if MORPH_TARGETS > 0
  // Morph targets before skinning (glTF 2.0 §3.7.2.2).
  for (uint m = 0u; m < uint(MORPH_TARGETS); ++m) {
    const float w = morph_weight[f * uint(MORPH_TARGETS) + m];
    if (w == 0.0) continue;
    const uint base = 3u * (m * vertex_count + v);
    p += w * vec3(morph_offset[base], morph_offset[base + 1u], morph_offset[base + 2u]);
#ifdef HAS_NORMALS
    const uint nb = base + 3u * uint(MORPH_TARGETS) * vertex_count;
    n += w * vec3(morph_offset[nb], morph_offset[nb + 1u], morph_offset[nb + 2u]);
#endif
#ifdef HAS_TANGENTS
    const uint tb = base + 6u * uint(MORPH_TARGETS) * vertex_count;
    t += w * vec3(morph_offset[tb], morph_offset[tb + 1u], morph_offset[tb + 2u]);
#endif
  }
#endif

  // Influences, weights divided by their sum; none at all leaves the vertex in the bind pose.
  const uint record = v * uint(INFLUENCES + INFLUENCES / 2);
  int joint[INFLUENCES];
  float weight[INFLUENCES];
  float sum = 0.0;
  int pivot = 0;
  for (int k = 0; k < INFLUENCES; ++k) {
    const uint pair = influence[record + uint(k / 2)];
    joint[k] = int((k % 2 == 0) ? (pair & 0xFFFFu) : (pair >> 16));
    weight[k] = max(uintBitsToFloat(influence[record + uint(INFLUENCES / 2 + k)]), 0.0);
    sum += weight[k];
    if (weight[k] > weight[pivot]) pivot = k;
  }

  if (sum > 0.0) {
#if defined(MODE_LBS)
    // Linear blend of the joint matrices [R S | t], rebuilt from the texture.
    mat3 a = mat3(0.0);
    vec3 translation = vec3(0.0);
    for (int k = 0; k < INFLUENCES; ++k) {
      if (weight[k] <= 0.0) continue;
      const vec4 r = bone(joint[k], 0, row), d = bone(joint[k], 1, row);
      const mat3 rot = mat3(quat_rotate(r, vec3(1, 0, 0)), quat_rotate(r, vec3(0, 1, 0)), quat_rotate(r, vec3(0, 0, 1)));
      const float w = weight[k] / sum;
      a += w * (rot * bone_scale(joint[k], row));
      translation += w * 2.0 * (r.w * d.xyz - d.w * r.xyz + cross(r.xyz, d.xyz));
    }
    p = a * p + translation;
#ifdef HAS_NORMALS
    n = cofactor(a) * n;
#endif
#ifdef HAS_TANGENTS
    t = a * t;
#endif
#else
    // DLB with every influence flipped to the pivot's hemisphere (docs/DESIGN.md §3.5, antipodality).
    const vec4 pivot_real = bone(joint[pivot], 0, row);
    vec4 real = vec4(0.0), dual = vec4(0.0);
    mat3 s = mat3(0.0);
    for (int k = 0; k < INFLUENCES; ++k) {
      if (weight[k] <= 0.0) continue;
      const vec4 r = bone(joint[k], 0, row), d = bone(joint[k], 1, row);
      const float w = (dot(r, pivot_real) < 0.0 ? -weight[k] : weight[k]) / sum;
      real += w * r;
      dual += w * d;
#if TEXELS == 5
      s += (weight[k] / sum) * bone_scale(joint[k], row);
#endif
    }
    const float len = length(real);
    real /= len;
    dual /= len;  // the part of dual along real does not move points, so no projection is needed
    const vec3 translation = 2.0 * (real.w * dual.xyz - dual.w * real.xyz + cross(real.xyz, dual.xyz));
#if TEXELS == 5
    p = s * p;
#ifdef HAS_NORMALS
    n = cofactor(s) * n;
#endif
#ifdef HAS_TANGENTS
    t = s * t;
#endif
#endif
    p = quat_rotate(real, p) + translation;
#ifdef HAS_NORMALS
    n = quat_rotate(real, n);
#endif
#ifdef HAS_TANGENTS
    t = quat_rotate(real, t);
#endif
#endif
  }

  const uint o = 3u * (f * vertex_count + v);
  out_position[o] = p.x;
  out_position[o + 1u] = p.y;
  out_position[o + 2u] = p.z;
#ifdef HAS_NORMALS
  const float nl = length(n);
  if (nl > 0.0) n /= nl;
  out_normal[o] = n.x;
  out_normal[o + 1u] = n.y;
  out_normal[o + 2u] = n.z;
#endif
#ifdef HAS_TANGENTS
  const float tl = length(t);
  if (tl > 0.0) t /= tl;
  out_tangent[f * vertex_count + v] = vec4(t, tangent.w);
#endif
}
