#version 300 es
// Test wrapper (glsl/kits/check_kits.py): the Godot kit's functions (dqskin.gdshaderinc, pasted where the
// include is) in a GLSL ES 3.00 vertex shader that calls every one, for glslangValidator. GLSL ES 3.00, the
// language Godot's derives from, has no implicit int-to-float conversions, as Godot has none.
precision highp float;
precision highp int;
precision highp sampler2D;
#include "dqskin.gdshaderinc"

uniform sampler2D positions;
uniform sampler2D normals;
uniform sampler2D bones;
uniform sampler2D sockets;
in vec3 position;
in vec3 normal;
in vec2 uv1;
in vec4 joints;
in vec4 weights;
in vec4 clip;
out vec3 world_normal;

void main() {
  float frame;
  float last;
  float frame_b;
  float last_b;
  dqskin_clip_frame(clip.x, clip.y, clip.z, clip.w, 1.0, frame, last);
  dqskin_clip_frame(clip.x, clip.z, clip.y, clip.w, 0.0, frame_b, last_b);
  vec3 p, n, pc, nc, ps, ns, pm, nm, sp, spc;
  vec4 sr, src, r0, r1, r2;
  dqskin_vat(positions, normals, uv1, frame, last, 2.0, p, n);
  dqskin_vat_crossfade(positions, normals, uv1, frame, last, frame_b, last_b, 0.5, 2.0, pc, nc);
  dqskin_dq_skin(bones, 5.0, joints, weights, frame, frame_b, 0.5, position, normal, ps, ns);
  dqskin_matrix_skin(bones, 4.0, joints, weights, frame, frame_b, 0.5, position, normal, pm, nm);
  vec3 p8, n8, pm8, nm8;
  dqskin_dq_skin8(bones, 5.0, joints, weights, weights, joints, frame, frame_b, 0.5, position, normal, p8, n8);
  dqskin_matrix_skin8(bones, 3.0, joints, weights, weights, joints, frame, frame_b, 0.5, position, normal, pm8, nm8);
  dqskin_socket(sockets, 2.0, frame, last, sp, sr);
  dqskin_socket_crossfade(sockets, 2.0, frame, last, frame_b, last_b, 0.25, spc, src);
  dqskin_socket_matrix(sockets, 2.0, frame, last, r0, r1, r2);
  vec4 sum = vec4(p + pc + ps + pm + sp + spc + sr.xyz + src.xyz, 1.0);
  gl_Position = vec4(dot(r0, sum), dot(r1, sum), dot(r2, sum), 1.0);
  world_normal = n + nc + ns + nm + p8 + n8 + pm8 + nm8;
}
