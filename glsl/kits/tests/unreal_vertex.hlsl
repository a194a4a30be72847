// Test wrapper (glsl/kits/check_kits.py): a vertex shader that calls every function of the Unreal kit
// (Dqskin.ush) as a material Custom node would, with Texture2D parameters, so that glslangValidator's HLSL
// front end type-checks them.
#include "Dqskin.ush"

Texture2D Positions;
Texture2D Normals;
Texture2D Bones;
Texture2D Sockets;

struct VertexOut {
  float4 position : SV_Position;
  float3 normal : NORMAL;
};

VertexOut main(float3 position : POSITION, float3 normal : NORMAL, float2 uv1 : TEXCOORD1, float4 joints : TEXCOORD2,
               float4 weights : TEXCOORD3, float4 clip : TEXCOORD4)
{
  float frame, last, frame_b, last_b;
  dqskin_clip_frame(clip.x, clip.y, clip.z, clip.w, 1.0, frame, last);
  dqskin_clip_frame(clip.x, clip.z, clip.y, clip.w, 0.0, frame_b, last_b);
  float3 p, n, pc, nc, ps, ns, pm, nm, sp, spc;
  float4 sr, src, r0, r1, r2;
  dqskin_vat(Positions, Normals, uv1, frame, last, 2.0, p, n);
  dqskin_vat_crossfade(Positions, Normals, uv1, frame, last, frame_b, last_b, 0.5, 2.0, pc, nc);
  dqskin_dq_skin(Bones, 5.0, joints, weights, frame, frame_b, 0.5, position, normal, ps, ns);
  dqskin_matrix_skin(Bones, 3.0, joints, weights, frame, frame_b, 0.5, position, normal, pm, nm);
  float3 p8, n8, pm8, nm8;
  dqskin_dq_skin8(Bones, 5.0, joints, weights, weights, joints, frame, frame_b, 0.5, position, normal, p8, n8);
  dqskin_matrix_skin8(Bones, 3.0, joints, weights, weights, joints, frame, frame_b, 0.5, position, normal, pm8, nm8);
  dqskin_socket(Sockets, 2.0, frame, last, sp, sr);
  dqskin_socket_crossfade(Sockets, 2.0, frame, last, frame_b, last_b, 0.25, spc, src);
  dqskin_socket_matrix(Sockets, 2.0, frame, last, r0, r1, r2);
  VertexOut o;
  float4 sum = float4(p + pc + ps + pm + sp + spc + sr.xyz + src.xyz, 1.0);
  o.position = float4(dot(r0, sum), dot(r1, sum), dot(r2, sum), 1.0);
  o.normal = n + nc + ns + nm + p8 + n8 + pm8 + nm8;
  return o;
}
