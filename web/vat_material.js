// Vertex-animation textures as the runtimes the profiles come from read them (docs/formats.md, "Texture
// profiles"; each bake's vat.json names the files): the rest mesh's TEXCOORD_1 addresses frame 0, and the
// shader steps down the texture by frames.
//   openvat: OpenVAT's engine decoders (its Godot shader): offset = Min + texel.rgb (Max - Min) from
//            NAME-remap_info.json, in Blender's axes, added to the rest position; v steps 1 / height per
//            frame; packed normals sit half the image lower, separate ones in NAME_vnrm at the same texel.
//   houdini: SideFX Labs VAT 3.0 "Soft" (its Unity shader): the HDR texel is the offset from the first
//            frame; v steps 1 / FrameCount per frame, scaled by the used part of a padded texture; the
//            normal is the rotation texture's quaternion applied to +Y, or the 10-bit spheremap code in
//            the position alpha.
// Between frames both runtimes blend the decoded neighbours linearly. A crossfade (defines BLEND: the
// player's blend=) lerps the decoded frame with a second one, blend_frame, by blend_weight, normals
// renormalized: the VAT crossfade of docs/DESIGN.md §3.10 (lib/skin/crossfade.cpp, vat_crossfade).
import * as THREE from 'three';
import { normalsFragment } from './shading.js';

const vertex = /* glsl */ `
precision highp float;
precision highp sampler2D;
in vec3 position;
in vec3 normal;
in vec2 uv1;  // TEXCOORD_1: the texel centre of this vertex in frame 0
uniform mat4 modelMatrix, viewMatrix, projectionMatrix;
uniform sampler2D positions;
uniform sampler2D normals;   // the position texture again when the normals are packed into it
uniform float frame;         // frames from the clip's first, fractional between frames
uniform float last_frame;
uniform vec2 frame_step;     // texture coordinates from one frame to the next
uniform vec2 uv_scale;       // Houdini: the used part of a padded texture; (1, 1) otherwise
uniform vec2 normal_shift;   // OpenVAT packed: (0, 0.5)
uniform vec3 remap_min, remap_max;
uniform float blend_frame;   // BLEND: the second frame (a whole frame of the texture)
uniform float blend_weight;  // BLEND: its weight w; the first frame has 1 − w
out vec3 world_position;
out vec3 world_normal;

vec3 quat_rotate(vec4 q, vec3 v) { return v + 2.0 * cross(q.xyz, cross(q.xyz, v) + q.w * v); }

#if defined(OPENVAT)
vec3 blender_to_gltf(vec3 v) { return vec3(v.x, v.z, -v.y); }
#endif

vec2 lookup(float f) { return (uv1 + f * frame_step) * uv_scale; }

vec3 offset_at(float f) {
  vec4 t = textureLod(positions, lookup(f), 0.0);
#if defined(OPENVAT)
  return blender_to_gltf(remap_min + t.rgb * (remap_max - remap_min));
#else
  return t.rgb;
#endif
}

vec3 normal_at(float f) {
#if defined(OPENVAT)
  return normalize(blender_to_gltf(textureLod(normals, lookup(f) + normal_shift, 0.0).rgb * 2.0 - 1.0));
#elif defined(HOUDINI_PACKED)
  // Labs VAT 3.0's decode of the spheremap code in alpha (10 bits: 5 for x, the rest for y).
  float a = textureLod(positions, lookup(f), 0.0).a * 1024.0;
  vec2 v = vec2(floor(a / 32.0), a - floor(a / 32.0) * 32.0) / 31.5 * 4.0 - 2.0;
  float d = dot(v, v);
  vec2 xy = v * sqrt(max(0.0, 1.0 - d / 4.0));
  return normalize(clamp(vec3(xy.x, 1.0 - d / 2.0, xy.y), -1.0, 1.0));
#else
  return normalize(quat_rotate(textureLod(normals, lookup(f), 0.0), vec3(0.0, 1.0, 0.0)));
#endif
}

void main() {
  float f0 = floor(frame), f1 = min(f0 + 1.0, last_frame), s = frame - f0;
  vec3 p = position + mix(offset_at(f0), offset_at(f1), s);
#if defined(BLEND)
  p = mix(p, position + offset_at(blend_frame), blend_weight);
#endif
#if defined(HAS_NORMALS)
  vec3 n = normalize(mix(normal_at(f0), normal_at(f1), s));
#if defined(BLEND)
  n = normalize(mix(n, normal_at(blend_frame), blend_weight));
#endif
  world_normal = normalize(mat3(modelMatrix) * n);
#else
  world_normal = vec3(0.0);
#endif
  vec4 world = modelMatrix * vec4(p, 1.0);
  world_position = world.xyz;
  gl_Position = projectionMatrix * viewMatrix * world;
}`;

// side: the bake's vat.json; profileFile: the profile's own side file (parsed); textures: { positions,
// normals? } DataTextures. Returns a material whose `uniforms.frame` selects the frame; options.blend makes
// it crossfade with `uniforms.blend_frame` by `uniforms.blend_weight`.
export function vatMaterial(side, profileFile, textures, options = {}) {
  const defines = {};
  if (options.blend) defines.BLEND = '';
  const uniforms = {
    positions: { value: textures.positions },
    normals: { value: textures.normals ?? textures.positions },
    frame: { value: 0 },
    last_frame: { value: 0 },
    frame_step: { value: new THREE.Vector2() },
    uv_scale: { value: new THREE.Vector2(1, 1) },
    normal_shift: { value: new THREE.Vector2() },
    remap_min: { value: new THREE.Vector3() },
    remap_max: { value: new THREE.Vector3() },
    blend_frame: { value: 0 },
    blend_weight: { value: 0 },
  };
  const height = textures.positions.image.height;
  if (side.profile === 'openvat') {
    const remap = profileFile['os-remap'];
    defines.OPENVAT = '';
    uniforms.remap_min.value.fromArray(remap.Min);
    uniforms.remap_max.value.fromArray(remap.Max);
    uniforms.last_frame.value = remap.Frames - 1;
    uniforms.frame_step.value.set(0, 1 / height);
    if (side.normals === 'packed') uniforms.normal_shift.value.set(0, 0.5);
    if (side.normals === 'packed' || side.normals === 'separate') defines.HAS_NORMALS = '';
  } else if (side.profile === 'houdini') {
    const data = profileFile[0];
    // Labs' HDR flag, from the encoded bounds: frac(10 · Bound Max Z) ≥ 0.5.
    const boundMaxZ = data['Bound Max Z'];
    if (!(10 * boundMaxZ - Math.floor(10 * boundMaxZ) >= 0.5 - 1e-9))
      throw new Error('Houdini VAT: the player reads HDR (EXR) position textures only');
    uniforms.last_frame.value = data['Frame Count'] - 1;
    uniforms.frame_step.value.set(0, 1 / data['Frame Count']);
    uniforms.uv_scale.value.set(side.used_width / side.width, side.used_height / side.height);
    if (side.normals === 'packed') defines.HOUDINI_PACKED = '';
    if (side.normals !== 'none') defines.HAS_NORMALS = '';
  } else {
    throw new Error(`vat.json: profile '${side.profile}' is not one the player reads (openvat, houdini)`);
  }
  const material = new THREE.RawShaderMaterial({
    glslVersion: THREE.GLSL3,
    vertexShader: vertex,
    fragmentShader: normalsFragment,
    defines,
    uniforms: { ...uniforms, has_normals: { value: 'HAS_NORMALS' in defines } },
    side: THREE.DoubleSide,
  });
  return material;
}
