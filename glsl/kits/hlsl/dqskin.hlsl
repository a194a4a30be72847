// dqskin shader kit, HLSL core: the reading shader of each layout `dqskin bake` writes, as plain functions
// (Unity: Dqskin.hlsl, used by DqskinShaderGraph.hlsl; Unreal: Dqskin.ush for a material Custom node).
// The formulas are the player's and the bake's decode-back check's (docs/formats.md, "Texture profiles",
// "Shader kits"; docs/DESIGN.md §4.1 to §4.3 and §4.9): keep them identical to web/bones_material.js.
//
// Textures are read with Load at integer texels, as the layouts are meant to be read: import them linear
// (no sRGB), without mipmaps or compression (float or half EXR). Texel rows count from the image's top, as
// dqskin writes them; an engine that stores images bottom row first (Unity) defines DQSKIN_ROWS_FROM_BOTTOM
// before including this file. Quaternions are (x, y, z, w), w the scalar part.
#ifndef DQSKIN_HLSL_INCLUDED
#define DQSKIN_HLSL_INCLUDED

// ---- Texels -------------------------------------------------------------------------------------------

// The texel at column x, row y (rows from the image's top).
float4 dqskin_load(Texture2D tex, int x, int y)
{
#if defined(DQSKIN_ROWS_FROM_BOTTOM)
  uint width, height;
  tex.GetDimensions(width, height);
  y = int(height) - 1 - y;
#endif
  return tex.Load(int3(x, y, 0));
}

int dqskin_int(float v) { return int(floor(v + 0.5)); }

int dqskin_height(Texture2D tex)
{
  uint width, height;
  tex.GetDimensions(width, height);
  return int(height);
}

// ---- Clip table (docs/DESIGN.md §4.9) ----------------------------------------------------------------

// The texture's fractional frame of a clip at `time` seconds: first_frame + time · fps, clamped to the
// clip's frames, or wrapped when it loops (a looping clip's last pose is its first, so the period is
// frame_count − 1 frames). `last_frame` is the clip's last frame in the texture (for interpolation).
void dqskin_clip_frame(float time, float first_frame, float frame_count, float fps, float loop_flag,
                       out float frame, out float last_frame)
{
  float last = max(frame_count - 1.0, 0.0);
  float local = time * fps;
  if (loop_flag > 0.5 && last > 0.0) local = local - last * floor(local / last);
  else local = clamp(local, 0.0, last);
  frame = first_frame + local;
  last_frame = first_frame + last;
}

// The two frames a fractional frame lies between and the weight of the second, never past last_frame.
void dqskin_frame_pair(float frame, float last_frame, out float f0, out float f1, out float s)
{
  f0 = floor(frame);
  f1 = min(f0 + 1.0, last_frame);
  s = frame - f0;
}

// ---- Quaternions and dual quaternions (docs/DESIGN.md §3.1) -------------------------------------------

float3 dqskin_quat_rotate(float4 q, float3 v) { return v + 2.0 * cross(q.xyz, cross(q.xyz, v) + q.w * v); }

// The translation of a unit dual quaternion: 2 · dual · conj(real), vector part.
float3 dqskin_dq_translation(float4 r, float4 d) { return 2.0 * (r.w * d.xyz - d.w * r.xyz + cross(r.xyz, d.xyz)); }

// a · v for the matrix of columns a0, a1, a2, and cofactor(a) · v (how normals transform under a), written
// as GLSL's mat3 products are, so that the sums run in the player's order.
float3 dqskin_mul_columns(float3 a0, float3 a1, float3 a2, float3 v) { return a0 * v.x + a1 * v.y + a2 * v.z; }
float3 dqskin_mul_cofactor(float3 a0, float3 a1, float3 a2, float3 v)
{
  return dqskin_mul_columns(cross(a1, a2), cross(a2, a0), cross(a0, a1), v);
}

// n normalized, or `fallback` where it vanishes (two opposite normals lerped halfway): docs/DESIGN.md §3.10.
float3 dqskin_normalize_or(float3 n, float3 fallback)
{
  float len = length(n);
  return len > 0.0 ? n / len : fallback;
}

// ---- dqskin VAT (docs/DESIGN.md §4.3) -----------------------------------------------------------------
// texel0: the rest mesh's TEXCOORD_1, the integer texel of the vertex in frame 0; rows_per_frame: vat.json's
// rows_per_frame. Positions are absolute (world space of the bake), normals world-space; float or half EXR,
// one page (with pages, bind the page holding the clip: its clip-table entry's first_page).

int2 dqskin_vat_texel(float2 texel0, float frame, float rows_per_frame)
{
  return int2(dqskin_int(texel0.x), dqskin_int(texel0.y) + int(frame) * dqskin_int(rows_per_frame));
}

// The position and normal at a fractional frame, interpolated linearly between the neighbouring frames as
// every VAT runtime does (docs/DESIGN.md §4.4).
void dqskin_vat(Texture2D positions, Texture2D normals, float2 texel0, float frame, float last_frame,
                float rows_per_frame, out float3 position, out float3 normal)
{
  float f0, f1, s;
  dqskin_frame_pair(frame, last_frame, f0, f1, s);
  int2 t0 = dqskin_vat_texel(texel0, f0, rows_per_frame);
  int2 t1 = dqskin_vat_texel(texel0, f1, rows_per_frame);
  position = lerp(dqskin_load(positions, t0.x, t0.y).xyz, dqskin_load(positions, t1.x, t1.y).xyz, s);
  float3 n0 = dqskin_load(normals, t0.x, t0.y).xyz;
  normal = dqskin_normalize_or(lerp(n0, dqskin_load(normals, t1.x, t1.y).xyz, s), n0);
}

// Crossfade between clip A at frame_a and clip B at frame_b of one texture (docs/DESIGN.md §3.10):
// p = lerp(A, B, blend) per vertex, normals lerped and renormalized (A's where the lerp vanishes).
void dqskin_vat_crossfade(Texture2D positions, Texture2D normals, float2 texel0, float frame_a, float last_frame_a,
                          float frame_b, float last_frame_b, float blend, float rows_per_frame,
                          out float3 position, out float3 normal)
{
  float3 pa, na, pb, nb;
  dqskin_vat(positions, normals, texel0, frame_a, last_frame_a, rows_per_frame, pa, na);
  dqskin_vat(positions, normals, texel0, frame_b, last_frame_b, rows_per_frame, pb, nb);
  position = lerp(pa, pb, blend);
  normal = dqskin_normalize_or(lerp(na, nb, blend), na);
}

// ---- dq bone texture (docs/DESIGN.md §4.1) ------------------------------------------------------------
// Texel (T·j + k, row) holds component k of joint j: real, dual, then with T = 5 the rows of S (.xyz).
// `texels` is bones_skinK.json's texels_per_joint; `row` the frame's row (a clip's first_frame + frame).

// One joint's dual quaternion and scale/shear rows, crossfaded between row_a and row_b by `blend`
// (docs/DESIGN.md §3.10, as web/bones_material.js): B is flipped into A's hemisphere, real and dual lerped
// and divided by the real part's length, the dual part made orthogonal to it (a unit dual quaternion);
// S lerped. With blend = 0 the texels of row_a as they are.
void dqskin_dq_joint(Texture2D bones, float texels, float joint, float row_a, float row_b, float blend,
                     out float4 real, out float4 dual, out float3 s0, out float3 s1, out float3 s2)
{
  int t = dqskin_int(texels), x = t * dqskin_int(joint), ya = dqskin_int(row_a), yb = dqskin_int(row_b);
  float4 ra = dqskin_load(bones, x, ya), da = dqskin_load(bones, x + 1, ya);
  float4 rb = dqskin_load(bones, x, yb), db = dqskin_load(bones, x + 1, yb);
  float sign_b = dot(ra, rb) < 0.0 ? -1.0 : 1.0;
  real = ra;
  dual = da;
  if (blend != 0.0) {
    real = (1.0 - blend) * ra + blend * sign_b * rb;
    float len = length(real);
    real /= len;
    dual = ((1.0 - blend) * da + blend * sign_b * db) / len;
    dual -= dot(real, dual) * real;
  }
  s0 = float3(1.0, 0.0, 0.0);
  s1 = float3(0.0, 1.0, 0.0);
  s2 = float3(0.0, 0.0, 1.0);
  if (t == 5) {
    s0 = lerp(dqskin_load(bones, x + 2, ya).xyz, dqskin_load(bones, x + 2, yb).xyz, blend);
    s1 = lerp(dqskin_load(bones, x + 3, ya).xyz, dqskin_load(bones, x + 3, yb).xyz, blend);
    s2 = lerp(dqskin_load(bones, x + 4, ya).xyz, dqskin_load(bones, x + 4, yb).xyz, blend);
  }
}

// Influence k of eight: k < 4 from the first set (glTF JOINTS_0 / WEIGHTS_0), else the second (JOINTS_1 / WEIGHTS_1).
float dqskin_pick(float4 first, float4 second, int k) { return k < 4 ? first[k & 3] : second[k & 3]; }

// Dual-quaternion skinning of one vertex with up to eight influences (bones_mesh.glb's _JOINTS_0 /
// _WEIGHTS_0 and _JOINTS_1 / _WEIGHTS_1): DLB (Kavan et al. 2008, §4) with every influence flipped into the
// hemisphere of the heaviest (docs/DESIGN.md §3.5), and two-phase scale: p' = DLB(rigid) applied to
// (Σ w S) p, the normal by the cofactor of Σ w S. Crossfade: each joint's dual quaternion is first blended
// between row_a and row_b (dqskin_dq_joint); without one pass row_b = row_a and blend = 0.
void dqskin_dq_skin8(Texture2D bones, float texels, float4 joints0, float4 weights0, float4 joints1, float4 weights1,
                     float row_a, float row_b, float blend, float3 position, float3 normal, out float3 skinned_position,
                     out float3 skinned_normal)
{
  skinned_position = position;
  skinned_normal = normal;
  float sum = 0.0;
  int pivot = 0;
  [unroll] for (int k = 0; k < 8; ++k) {
    sum += max(dqskin_pick(weights0, weights1, k), 0.0);
    if (max(dqskin_pick(weights0, weights1, k), 0.0) > max(dqskin_pick(weights0, weights1, pivot), 0.0)) pivot = k;
  }
  if (sum <= 0.0) return;
  float4 pivot_real, unused_dual;
  float3 u0, u1, u2;
  dqskin_dq_joint(bones, texels, dqskin_pick(joints0, joints1, pivot), row_a, row_b, blend, pivot_real, unused_dual,
                  u0, u1, u2);
  float4 real = float4(0.0, 0.0, 0.0, 0.0), dual = float4(0.0, 0.0, 0.0, 0.0);
  float3 s0 = float3(0.0, 0.0, 0.0), s1 = float3(0.0, 0.0, 0.0), s2 = float3(0.0, 0.0, 0.0);
  [unroll] for (int i = 0; i < 8; ++i) {
    float weight = max(dqskin_pick(weights0, weights1, i), 0.0);
    if (weight <= 0.0) continue;
    float4 r, d;
    float3 j0, j1, j2;
    dqskin_dq_joint(bones, texels, dqskin_pick(joints0, joints1, i), row_a, row_b, blend, r, d, j0, j1, j2);
    float w = (dot(r, pivot_real) < 0.0 ? -weight : weight) / sum;
    real += w * r;
    dual += w * d;
    s0 += weight / sum * j0;
    s1 += weight / sum * j1;
    s2 += weight / sum * j2;
  }
  float len = length(real);
  real /= len;
  dual /= len;
  float3 p = position, n = normal;
  if (dqskin_int(texels) == 5) {
    // S is symmetric: its rows are its columns.
    p = dqskin_mul_columns(s0, s1, s2, position);
    n = dqskin_mul_cofactor(s0, s1, s2, normal);
  }
  skinned_position = dqskin_quat_rotate(real, p) + dqskin_dq_translation(real, dual);
  skinned_normal = dqskin_quat_rotate(real, n);
}

// The same with four influences (glTF JOINTS_0 / WEIGHTS_0).
void dqskin_dq_skin(Texture2D bones, float texels, float4 joints, float4 weights, float row_a, float row_b,
                    float blend, float3 position, float3 normal, out float3 skinned_position, out float3 skinned_normal)
{
  float4 none = float4(0.0, 0.0, 0.0, 0.0);
  dqskin_dq_skin8(bones, texels, joints, weights, none, none, row_a, row_b, blend, position, normal, skinned_position,
                  skinned_normal);
}

// ---- mat3x4 and mat4 bone textures (docs/DESIGN.md §4.2) ----------------------------------------------
// mat3x4 (texels = 3): texel (3j + k, row) is row k of the joint's affine matrix; mat4 (texels = 4): texel
// (4j + k, height − 1 − row) is column k of its 4x4 matrix (mat4 stores its frames bottom-up, as Babylon.js
// reads them). Linear blend skinning with the weights as given (PlayCanvas and
// Babylon.js do not renormalize them); the normal by the blended 3x3 itself, as they transform it; a crossfade
// lerps the matrices.

void dqskin_matrix_joint(Texture2D bones, float texels, float joint, float row, out float4 m0, out float4 m1,
                         out float4 m2)
{
  int t = dqskin_int(texels), x = t * dqskin_int(joint), y = dqskin_int(row);
  if (t == 4) {
    y = dqskin_height(bones) - 1 - y;
    float4 c0 = dqskin_load(bones, x, y), c1 = dqskin_load(bones, x + 1, y);
    float4 c2 = dqskin_load(bones, x + 2, y), c3 = dqskin_load(bones, x + 3, y);
    m0 = float4(c0.x, c1.x, c2.x, c3.x);
    m1 = float4(c0.y, c1.y, c2.y, c3.y);
    m2 = float4(c0.z, c1.z, c2.z, c3.z);
  } else {
    m0 = dqskin_load(bones, x, y);
    m1 = dqskin_load(bones, x + 1, y);
    m2 = dqskin_load(bones, x + 2, y);
  }
}

void dqskin_matrix_skin8(Texture2D bones, float texels, float4 joints0, float4 weights0, float4 joints1,
                         float4 weights1, float row_a, float row_b, float blend, float3 position, float3 normal,
                         out float3 skinned_position, out float3 skinned_normal)
{
  float4 m0 = float4(0.0, 0.0, 0.0, 0.0), m1 = m0, m2 = m0;
  float sum = 0.0;
  [unroll] for (int k = 0; k < 8; ++k) sum += max(dqskin_pick(weights0, weights1, k), 0.0);
  skinned_position = position;
  skinned_normal = normal;
  if (sum <= 0.0) return;
  [unroll] for (int i = 0; i < 8; ++i) {
    float w = max(dqskin_pick(weights0, weights1, i), 0.0);
    if (w <= 0.0) continue;
    float4 a0, a1, a2, b0, b1, b2;
    dqskin_matrix_joint(bones, texels, dqskin_pick(joints0, joints1, i), row_a, a0, a1, a2);
    dqskin_matrix_joint(bones, texels, dqskin_pick(joints0, joints1, i), row_b, b0, b1, b2);
    m0 += w * lerp(a0, b0, blend);
    m1 += w * lerp(a1, b1, blend);
    m2 += w * lerp(a2, b2, blend);
  }
  float4 p = float4(position, 1.0);
  skinned_position = float3(dot(m0, p), dot(m1, p), dot(m2, p));
  skinned_normal = float3(dot(m0.xyz, normal), dot(m1.xyz, normal), dot(m2.xyz, normal));
}

void dqskin_matrix_skin(Texture2D bones, float texels, float4 joints, float4 weights, float row_a, float row_b,
                        float blend, float3 position, float3 normal, out float3 skinned_position,
                        out float3 skinned_normal)
{
  float4 none = float4(0.0, 0.0, 0.0, 0.0);
  dqskin_matrix_skin8(bones, texels, joints, weights, none, none, row_a, row_b, blend, position, normal,
                      skinned_position, skinned_normal);
}

// ---- Sockets (sockets.exr, sockets.json) --------------------------------------------------------------
// Row f is frame f (with combined textures the clip table applies); socket s has 5 texels: 5s + 0..2 the
// rows of its joint's 3x4 world matrix, 5s + 3 the dual quaternion's real part, 5s + 4 its dual part.

void dqskin_socket_dq(Texture2D sockets, float socket, float frame, float last_frame, out float4 real, out float4 dual)
{
  float f0, f1, s;
  dqskin_frame_pair(frame, last_frame, f0, f1, s);
  int x = 5 * dqskin_int(socket);
  float4 r0 = dqskin_load(sockets, x + 3, int(f0)), d0 = dqskin_load(sockets, x + 4, int(f0));
  float4 r1 = dqskin_load(sockets, x + 3, int(f1)), d1 = dqskin_load(sockets, x + 4, int(f1));
  // DLB of the two frames, the second flipped into the first's hemisphere, normalized.
  float sign1 = dot(r0, r1) < 0.0 ? -1.0 : 1.0;
  real = (1.0 - s) * r0 + s * sign1 * r1;
  dual = (1.0 - s) * d0 + s * sign1 * d1;
  float len = length(real);
  real /= len;
  dual /= len;
}

// The socket's position and rotation (a unit quaternion) at a fractional frame.
void dqskin_socket(Texture2D sockets, float socket, float frame, float last_frame, out float3 position,
                   out float4 rotation)
{
  float4 real, dual;
  dqskin_socket_dq(sockets, socket, frame, last_frame, real, dual);
  position = dqskin_dq_translation(real, dual);
  rotation = real;
}

// The same, crossfaded between two clips (or frames) by `blend`, as the dq bone texture blends a joint.
void dqskin_socket_crossfade(Texture2D sockets, float socket, float frame_a, float last_frame_a, float frame_b,
                             float last_frame_b, float blend, out float3 position, out float4 rotation)
{
  float4 ra, da, rb, db;
  dqskin_socket_dq(sockets, socket, frame_a, last_frame_a, ra, da);
  dqskin_socket_dq(sockets, socket, frame_b, last_frame_b, rb, db);
  float sign_b = dot(ra, rb) < 0.0 ? -1.0 : 1.0;
  float4 real = (1.0 - blend) * ra + blend * sign_b * rb, dual = (1.0 - blend) * da + blend * sign_b * db;
  float len = length(real);
  real /= len;
  dual /= len;
  position = dqskin_dq_translation(real, dual);
  rotation = real;
}

// The socket joint's world matrix (scale and shear included), its rows lerped between the two frames.
void dqskin_socket_matrix(Texture2D sockets, float socket, float frame, float last_frame, out float4 row0,
                          out float4 row1, out float4 row2)
{
  float f0, f1, s;
  dqskin_frame_pair(frame, last_frame, f0, f1, s);
  int x = 5 * dqskin_int(socket);
  row0 = lerp(dqskin_load(sockets, x, int(f0)), dqskin_load(sockets, x, int(f1)), s);
  row1 = lerp(dqskin_load(sockets, x + 1, int(f0)), dqskin_load(sockets, x + 1, int(f1)), s);
  row2 = lerp(dqskin_load(sockets, x + 2, int(f0)), dqskin_load(sockets, x + 2, int(f1)), s);
}

#endif  // DQSKIN_HLSL_INCLUDED
