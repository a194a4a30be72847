// A dqskin bone texture (profile `dq`, docs/DESIGN.md §4.1) skinned in the vertex shader: the
// GPU-crowd runtime the texture is for. Texel (T·j + k, f) holds component k of joint j at frame f: the
// real and dual parts of the joint's unit dual quaternion, then with T = 5 the rows of its scale/shear S.
// Blending is DLB (Kavan et al. 2008, §4) with every influence flipped into the hemisphere of the one with
// the largest weight (docs/DESIGN.md §3.5) and, for scale, two-phase skinning: p' = DLB(rigid) applied
// to (Σ w S) p, the normal by the cofactor of Σ w S. The same formulas as bones_skinK.json's "decode" and
// the compute shader's (glsl/skin.comp). A crossfade (defines BLEND: the player's blend=) first blends each
// joint's two rows, `row` and `blend_row`, by blend_weight: DLB of the two dual quaternions (the second
// flipped into the first's hemisphere; the same pose as the heavier-pivot rule of docs/DESIGN.md §3.5) and
// the S rows lerped, then skins with them as above: the DQ crossfade of docs/DESIGN.md §3.10
// (lib/skin/crossfade.cpp, dq_crossfade).
import * as THREE from 'three';
import { normalsFragment } from './shading.js';

const vertex = /* glsl */ `
precision highp float;
precision highp sampler2D;
in vec3 position;
in vec3 normal;
in vec4 _joints_0;   // glTF _JOINTS_0 / _WEIGHTS_0 of bones_mesh.glb (three.js lower-cases the names)
in vec4 _weights_0;
#if INFLUENCES == 8
in vec4 _joints_1;
in vec4 _weights_1;
#endif
uniform mat4 modelMatrix, viewMatrix, projectionMatrix;
uniform sampler2D bones;
uniform int row;     // the frame's row
uniform int blend_row;       // BLEND: the second frame's row
uniform float blend_weight;  // BLEND: its weight w; row has 1 − w
out vec3 world_position;
out vec3 world_normal;

vec3 quat_rotate(vec4 q, vec3 v) { return v + 2.0 * cross(q.xyz, cross(q.xyz, v) + q.w * v); }
mat3 cofactor(mat3 a) { return mat3(cross(a[1], a[2]), cross(a[2], a[0]), cross(a[0], a[1])); }
vec4 texel(int joint, int k, int r) { return texelFetch(bones, ivec2(TEXELS * joint + k, r), 0); }
mat3 scale_at(int joint, int r) {
#if TEXELS == 5
  // symmetric: rows are columns
  return mat3(texel(joint, 2, r).xyz, texel(joint, 3, r).xyz, texel(joint, 4, r).xyz);
#else
  return mat3(1.0);
#endif
}
#if defined(BLEND)
// The joint's real (k = 0) or dual (k = 1) part, blended: ((1 − w) qa + w s qb) / ‖·‖, the dual-number
// norm, so that the result is unit (real part of length 1, dual part orthogonal to it).
vec4 bone(int joint, int k) {
  vec4 ra = texel(joint, 0, row), rb = texel(joint, 0, blend_row);
  float wb = dot(ra, rb) < 0.0 ? -blend_weight : blend_weight, wa = 1.0 - blend_weight;
  vec4 real = wa * ra + wb * rb;
  float len = length(real);
  real /= len;
  if (k == 0) return real;
  vec4 dual = (wa * texel(joint, 1, row) + wb * texel(joint, 1, blend_row)) / len;
  return dual - dot(real, dual) * real;
}
mat3 bone_scale(int joint) {
  return (1.0 - blend_weight) * scale_at(joint, row) + blend_weight * scale_at(joint, blend_row);
}
#else
vec4 bone(int joint, int k) { return texel(joint, k, row); }
mat3 bone_scale(int joint) { return scale_at(joint, row); }
#endif
vec3 translation_of(vec4 r, vec4 d) { return 2.0 * (r.w * d.xyz - d.w * r.xyz + cross(r.xyz, d.xyz)); }

void main() {
  int joint[INFLUENCES];
  float weight[INFLUENCES];
  for (int k = 0; k < 4; ++k) {
    joint[k] = int(_joints_0[k] + 0.5);
    weight[k] = max(_weights_0[k], 0.0);
#if INFLUENCES == 8
    joint[k + 4] = int(_joints_1[k] + 0.5);
    weight[k + 4] = max(_weights_1[k], 0.0);
#endif
  }
  float sum = 0.0;
  int pivot = 0;
  for (int k = 0; k < INFLUENCES; ++k) {
    sum += weight[k];
    if (weight[k] > weight[pivot]) pivot = k;
  }
  vec3 p = position, n = normal;
  if (sum > 0.0) {
#if defined(FAULT_LBS)
    // A deliberately wrong decode for the tests: linear blending of the joint matrices.
    mat3 a = mat3(0.0);
    vec3 t = vec3(0.0);
    for (int k = 0; k < INFLUENCES; ++k) {
      if (weight[k] <= 0.0) continue;
      vec4 r = bone(joint[k], 0), d = bone(joint[k], 1);
      mat3 rot = mat3(quat_rotate(r, vec3(1, 0, 0)), quat_rotate(r, vec3(0, 1, 0)), quat_rotate(r, vec3(0, 0, 1)));
      a += weight[k] / sum * (rot * bone_scale(joint[k]));
      t += weight[k] / sum * translation_of(r, d);
    }
    p = a * p + t;
    n = cofactor(a) * n;
#else
    vec4 pivot_real = bone(joint[pivot], 0);
    vec4 real = vec4(0.0), dual = vec4(0.0);
    mat3 s = mat3(0.0);
    for (int k = 0; k < INFLUENCES; ++k) {
      if (weight[k] <= 0.0) continue;
      vec4 r = bone(joint[k], 0), d = bone(joint[k], 1);
      float w = (dot(r, pivot_real) < 0.0 ? -weight[k] : weight[k]) / sum;
      real += w * r;
      dual += w * d;
      s += weight[k] / sum * bone_scale(joint[k]);
    }
    float len = length(real);
    real /= len;
    dual /= len;
#if TEXELS == 5
    p = s * p;
    n = cofactor(s) * n;
#endif
    p = quat_rotate(real, p) + translation_of(real, dual);
    n = quat_rotate(real, n);
#endif
  }
  // The joint matrices map bind space to world space: the node's own transform does not apply (glTF 2.0
  // §3.7.3.3), and bones_mesh.glb's node has none.
  world_position = p;
  world_normal = n;
  gl_Position = projectionMatrix * viewMatrix * vec4(p, 1.0);
}`;

// texture: the skin's DataTexture; side: its bones_skinK.json; geometry: the primitive's. options.fault: 'lbs';
// options.blend: crossfade `uniforms.row` with `uniforms.blend_row` by `uniforms.blend_weight`.
export function bonesMaterial(texture, side, geometry, options = {}) {
  if (side.profile !== 'dq')
    throw new Error(`${side.file}: profile '${side.profile}'; the player skins the dq profile`);
  const influences = geometry.getAttribute('_joints_1') ? 8 : 4;
  const defines = { TEXELS: side.texels_per_joint, INFLUENCES: influences };
  if (options.fault === 'lbs') defines.FAULT_LBS = '';
  if (options.blend) defines.BLEND = '';
  return new THREE.RawShaderMaterial({
    glslVersion: THREE.GLSL3,
    vertexShader: vertex,
    fragmentShader: normalsFragment,
    defines,
    uniforms: {
      bones: { value: texture },
      row: { value: 0 },
      blend_row: { value: 0 },
      blend_weight: { value: 0 },
      has_normals: { value: geometry.getAttribute('normal') !== undefined },
    },
    side: THREE.DoubleSide,
  });
}
