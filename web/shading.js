// What every path draws: `dqskin render --shade normals` (glsl/render.frag), the world-space unit normal
// as colour, 0.5 n + 0.5, or the triangle's own normal where the mesh has none. dqskin writes that linear
// colour to an 8-bit sRGB PNG; here the canvas is 8-bit and three.js's colour management is off, so the
// shader encodes to sRGB itself, with the same curve (IEC 61966-2-1, as lib/base/srgb.hpp).
const srgbGlsl = /* glsl */ `
vec3 srgb_encode(vec3 c) {
  c = clamp(c, 0.0, 1.0);
  return mix(c * 12.92, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(vec3(0.0031308), c));
}`;

// The fragment stage shared by our own materials (GLSL ES 3.00, for a RawShaderMaterial).
export const normalsFragment = /* glsl */ `
precision highp float;
in vec3 world_position;
in vec3 world_normal;
uniform bool has_normals;
out vec4 color;
${srgbGlsl}
void main() {
  vec3 face = cross(dFdx(world_position), dFdy(world_position));
  vec3 n = has_normals ? normalize(world_normal) : normalize(face);
  color = vec4(srgb_encode(0.5 * n + 0.5), 1.0);
}`;
