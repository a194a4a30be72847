// Vertex stage of `dqskin render` (lib/render/renderer.cpp): deformed vertices arrive in world space, so
// only the camera's view-projection is applied. Compiled with "#version 430" prepended.

layout(location = 0) in vec3 position;  // world space
layout(location = 1) in vec3 normal;    // world space, unit; a constant when the primitive has none
layout(location = 2) in float scalar;   // Shade weights: the value shown as a heat map

uniform mat4 view_projection;

out vec3 world_position;
out vec3 world_normal;
out float vertex_scalar;

void main() {
  world_position = position;
  world_normal = normal;
  vertex_scalar = scalar;
  gl_Position = view_projection * vec4(position, 1.0);
}
