// Test wrapper (glsl/kits/check_kits.py): a vertex shader that calls every Shader Graph entry point of the
// Unity kit, so that glslangValidator's HLSL front end type-checks them as Shader Graph would call them.
// UnityTexture2D is Shader Graph's (com.unity.shadergraph, Texture.hlsl), declared here as it declares it.
struct UnityTexture2D {
  Texture2D tex;
  SamplerState samplerstate;
  float4 texelSize;
  float4 scaleTranslate;
};
#include "DqskinShaderGraph.hlsl"

Texture2D _Positions;
Texture2D _Normals;
SamplerState sampler_Positions;

struct VertexOut {
  float4 position : SV_Position;
  float3 normal : NORMAL;
};

VertexOut main(float3 position : POSITION, float3 normal : NORMAL, float2 uv1 : TEXCOORD1, float4 joints : TEXCOORD2,
               float4 weights : TEXCOORD3, float4 clip : TEXCOORD4)
{
  UnityTexture2D tex;
  tex.tex = _Positions;
  tex.samplerstate = sampler_Positions;
  tex.texelSize = float4(0.0, 0.0, 0.0, 0.0);
  tex.scaleTranslate = float4(1.0, 1.0, 0.0, 0.0);
  UnityTexture2D nrm = tex;
  nrm.tex = _Normals;

  float frame, last, frame_b, last_b;
  DqskinClipFrame_float(clip.x, clip.y, clip.z, clip.w, 1.0, frame, last);
  DqskinClipFrame_float(clip.x, clip.z, clip.y, clip.w, 0.0, frame_b, last_b);
  float3 p, n, pc, nc, ps, ns, pm, nm, sp, spc;
  float4 sr, src;
  float4x4 sm;
  DqskinVat_float(tex, nrm, uv1, 1.0, frame, last, 2.0, p, n);
  DqskinVatCrossfade_float(tex, nrm, uv1, 0.0, frame, last, frame_b, last_b, 0.5, 2.0, pc, nc);
  DqskinDqSkin_float(tex, 5.0, joints, weights, frame, frame_b, 0.5, position, normal, ps, ns);
  DqskinMatrixSkin_float(tex, 4.0, joints, weights, frame, frame_b, 0.5, position, normal, pm, nm);
  float3 p8, n8, pm8, nm8;
  DqskinDqSkin8_float(tex, 5.0, joints, weights, weights, joints, frame, frame_b, 0.5, position, normal, p8, n8);
  DqskinMatrixSkin8_float(tex, 3.0, joints, weights, weights, joints, frame, frame_b, 0.5, position, normal, pm8, nm8);
  DqskinSocket_float(tex, 1.0, frame, last, sp, sr);
  DqskinSocketCrossfade_float(tex, 1.0, frame, last, frame_b, last_b, 0.5, spc, src);
  DqskinSocketMatrix_float(tex, 1.0, frame, last, sm);

  half hf, hl;
  half3 hp, hn, hpc, hnc, hps, hns, hpm, hnm, hsp, hspc;
  half4 hsr, hsrc;
  half4x4 hsm;
  DqskinClipFrame_half(clip.x, clip.y, clip.z, clip.w, 1.0, hf, hl);
  DqskinVat_half(tex, nrm, uv1, 1.0, hf, hl, 2.0, hp, hn);
  DqskinVatCrossfade_half(tex, nrm, uv1, 0.0, hf, hl, hf, hl, 0.5, 2.0, hpc, hnc);
  DqskinDqSkin_half(tex, 2.0, joints, weights, hf, hf, 0.0, position, normal, hps, hns);
  DqskinMatrixSkin_half(tex, 3.0, joints, weights, hf, hf, 0.0, position, normal, hpm, hnm);
  half3 hp8, hn8, hpm8, hnm8;
  DqskinDqSkin8_half(tex, 2.0, joints, weights, weights, joints, hf, hf, 0.0, position, normal, hp8, hn8);
  DqskinMatrixSkin8_half(tex, 4.0, joints, weights, weights, joints, hf, hf, 0.0, position, normal, hpm8, hnm8);
  DqskinSocket_half(tex, 0.0, hf, hl, hsp, hsr);
  DqskinSocketCrossfade_half(tex, 0.0, hf, hl, hf, hl, 0.5, hspc, hsrc);
  DqskinSocketMatrix_half(tex, 0.0, hf, hl, hsm);

  VertexOut o;
  float3 sum = p + pc + ps + pm + sp + spc + sr.xyz + src.xyz + hp + hpc + hps + hpm + hsp + hspc + hsr.xyz + hsrc.xyz;
  o.position = mul(sm, float4(sum, 1.0)) + mul(float4x4(hsm), float4(sum, 1.0));
  o.normal = n + nc + ns + nm + hn + hnc + hns + hnm + p8 + n8 + pm8 + nm8 + hp8 + hn8 + hpm8 + hnm8;
  return o;
}
