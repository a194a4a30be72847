// Fragment stage of `dqskin render` (lib/draw/renderer.cpp). Writes linear color; the PNG writer
// converts to sRGB. SHADE_LIT, SHADE_NORMALS or SHADE_WEIGHTS is defined by the renderer.

in vec3 world_position;
in vec3 world_normal;
in float vertex_scalar;
in vec2 texture_uv;
in vec4 color_0;

uniform vec4 base_color;      // the material's baseColorFactor, linear
uniform bool has_texture;     // base_color_texture is bound
uniform sampler2D base_color_texture;  // sRGB: the GL returns linear color
uniform int alpha_mode;       // 0 opaque, 1 mask, 2 blend (glTF alphaMode)
uniform float alpha_cutoff;   // mask: fragments with a lower alpha are not drawn
uniform bool has_normals;     // false: the face normal from screen-space derivatives
uniform vec3 eye;             // camera position, world space
uniform vec3 key_direction;   // towards the key light, world space, unit

out vec4 color;

// A perceptually ordered heat map (dark blue, cyan, yellow, red) for t in [0, 1].
vec3 heat(float t) {
  t = clamp(t, 0.0, 1.0);
  const vec3 stops[4] = vec3[4](vec3(0.02, 0.02, 0.25), vec3(0.0, 0.6, 0.8), vec3(1.0, 0.85, 0.0), vec3(0.8, 0.0, 0.0));
  const float x = t * 3.0;
  const int i = min(int(x), 2);
  return mix(stops[i], stops[i + 1], x - float(i));
}

void main() {
  // The triangle's own normal, on the side that faces the camera (x right, y up in window coordinates,
  // so the cross product points towards the viewer whatever the winding).
  const vec3 face = cross(dFdx(world_position), dFdy(world_position));
  vec3 n = has_normals ? normalize(world_normal) : normalize(face);
#if defined(SHADE_NORMALS)
  color = vec4(0.5 * n + 0.5, 1.0);
#else
  // Two-sided: a surface seen from behind (open meshes, mirrored winding) is lit as its front. The side is
  // the triangle's, not the interpolated normal's: along a silhouette a smooth normal can point slightly
  // away from the eye on a triangle that faces it, and flipping it there lit the edge as if from above.
  if (dot(n, face) < 0.0) n = -n;
  const float diffuse = max(dot(n, key_direction), 0.0);
  // Ambient plus key; a fill from the camera keeps faces turned away from the key readable.
  const float fill = 0.2 * max(dot(n, normalize(eye - world_position)), 0.0);
  const float light = 0.15 + 0.65 * diffuse + fill;  // at most 1: a white material stays unclipped
#if defined(SHADE_WEIGHTS)
  color = vec4(heat(vertex_scalar) * (0.35 + 0.65 * light), 1.0);
#else
  // glTF 2.0 §3.9.2: base color = factor × texture × COLOR_0.
  vec4 albedo = base_color * color_0;
  if (has_texture) albedo *= texture(base_color_texture, texture_uv);
  if (alpha_mode == 1 && albedo.a < alpha_cutoff) discard;
  // Opaque ignores alpha; blend writes premultiplied color for GL_ONE, GL_ONE_MINUS_SRC_ALPHA.
  const float alpha = alpha_mode == 2 ? albedo.a : 1.0;
  color = vec4(albedo.rgb * light * alpha, alpha);
#endif
#endif
}
