// Vertex stage of `dqskin render` (lib/draw/renderer.cpp): deformed vertices arrive in world space, so
// only the camera's view-projection is applied. Compiled with "#version 430" prepended.

layout(location = 0) in vec3 position;  // world space
layout(location = 1) in vec3 normal;    // world space, unit; a constant when the primitive has none
layout(location = 2) in float scalar;   // Shade weights: the value shown as a heat map
layout(location = 3) in vec2 uv;        // the TEXCOORD_n set of the base color texture
layout(location = 4) in vec4 vertex_color;  // COLOR_0, linear; (1, 1, 1, 1) when the primitive has none

uniform mat4 view_projection;
uniform mat3 uv_transform;  // the base color texture's KHR_texture_transform (T · R · S), or the identity

out vec3 world_position;
out vec3 world_normal;
out float vertex_scalar;
out vec2 texture_uv;
out vec4 color_0;

void main() {
  world_position = position;
  world_normal = normal;
  vertex_scalar = scalar;
  // Affine, so transforming at the vertices equals transforming the interpolated UV.
  texture_uv = (uv_transform * vec3(uv, 1.0)).xy;
  color_0 = vertex_color;
  gl_Position = view_projection * vec4(position, 1.0);
}
