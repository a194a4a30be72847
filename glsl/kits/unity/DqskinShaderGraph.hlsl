// dqskin shader kit for Unity Shader Graph (10 and later): entry points for Custom Function nodes in File
// mode, Source = this file, Name = one of DqskinClipFrame, DqskinVat, DqskinVatCrossfade, DqskinDqSkin,
// DqskinDqSkin8, DqskinMatrixSkin, DqskinMatrixSkin8, DqskinSocket, DqskinSocketCrossfade, DqskinSocketMatrix
// (Shader Graph appends _float or _half; set the node's precision to Single: frame and row numbers past 2048
// do not survive half). Declare the node's ports in the order of the parameters below (inputs, then the `out` ones):
// Texture2D ports for the textures (they arrive as UnityTexture2D), Vector 1 to 4 for the others,
// Matrix 4 for DqskinSocketMatrix. The math is in Dqskin.hlsl (docs/formats.md, "Shader kits").
//
// Unity stores images bottom row first, so the rows dqskin counts from the top are flipped here. glTF
// importers that flip texture coordinates to Unity's convention (glTFast, UnityGLTF: v' = 1 − v) flip the
// rest mesh's TEXCOORD_1 too: pass UvFlipped = 1 with them, 0 with an importer that keeps glTF's v.
#ifndef DQSKIN_SHADER_GRAPH_INCLUDED
#define DQSKIN_SHADER_GRAPH_INCLUDED

#define DQSKIN_ROWS_FROM_BOTTOM
#include "Dqskin.hlsl"

// The integer texel of frame 0 from UV1 (the rest mesh's TEXCOORD_1) as the importer left it.
float2 dqskin_unity_texel0(float2 uv1, float uv_flipped) { return uv_flipped > 0.5 ? float2(uv1.x, 1.0 - uv1.y) : uv1; }

void DqskinClipFrame_float(float Time, float FirstFrame, float FrameCount, float Fps, float Loop, out float Frame,
                           out float LastFrame)
{
  dqskin_clip_frame(Time, FirstFrame, FrameCount, Fps, Loop, Frame, LastFrame);
}

void DqskinVat_float(UnityTexture2D Positions, UnityTexture2D Normals, float2 Uv1, float UvFlipped, float Frame,
                     float LastFrame, float RowsPerFrame, out float3 Position, out float3 Normal)
{
  dqskin_vat(Positions.tex, Normals.tex, dqskin_unity_texel0(Uv1, UvFlipped), Frame, LastFrame, RowsPerFrame,
             Position, Normal);
}

void DqskinVatCrossfade_float(UnityTexture2D Positions, UnityTexture2D Normals, float2 Uv1, float UvFlipped,
                              float FrameA, float LastFrameA, float FrameB, float LastFrameB, float Blend,
                              float RowsPerFrame, out float3 Position, out float3 Normal)
{
  dqskin_vat_crossfade(Positions.tex, Normals.tex, dqskin_unity_texel0(Uv1, UvFlipped), FrameA, LastFrameA, FrameB,
                       LastFrameB, Blend, RowsPerFrame, Position, Normal);
}

void DqskinDqSkin_float(UnityTexture2D Bones, float Texels, float4 Joints, float4 Weights, float RowA, float RowB,
                        float Blend, float3 Position, float3 Normal, out float3 SkinnedPosition,
                        out float3 SkinnedNormal)
{
  dqskin_dq_skin(Bones.tex, Texels, Joints, Weights, RowA, RowB, Blend, Position, Normal, SkinnedPosition,
                 SkinnedNormal);
}

void DqskinMatrixSkin_float(UnityTexture2D Bones, float Texels, float4 Joints, float4 Weights, float RowA,
                            float RowB, float Blend, float3 Position, float3 Normal, out float3 SkinnedPosition,
                            out float3 SkinnedNormal)
{
  dqskin_matrix_skin(Bones.tex, Texels, Joints, Weights, RowA, RowB, Blend, Position, Normal, SkinnedPosition,
                     SkinnedNormal);
}

void DqskinDqSkin8_float(UnityTexture2D Bones, float Texels, float4 Joints0, float4 Weights0, float4 Joints1,
                         float4 Weights1, float RowA, float RowB, float Blend, float3 Position, float3 Normal,
                         out float3 SkinnedPosition, out float3 SkinnedNormal)
{
  dqskin_dq_skin8(Bones.tex, Texels, Joints0, Weights0, Joints1, Weights1, RowA, RowB, Blend, Position, Normal,
                  SkinnedPosition, SkinnedNormal);
}

void DqskinMatrixSkin8_float(UnityTexture2D Bones, float Texels, float4 Joints0, float4 Weights0, float4 Joints1,
                             float4 Weights1, float RowA, float RowB, float Blend, float3 Position, float3 Normal,
                             out float3 SkinnedPosition, out float3 SkinnedNormal)
{
  dqskin_matrix_skin8(Bones.tex, Texels, Joints0, Weights0, Joints1, Weights1, RowA, RowB, Blend, Position, Normal,
                      SkinnedPosition, SkinnedNormal);
}

void DqskinSocket_float(UnityTexture2D Sockets, float Socket, float Frame, float LastFrame, out float3 Position,
                        out float4 Rotation)
{
  dqskin_socket(Sockets.tex, Socket, Frame, LastFrame, Position, Rotation);
}

void DqskinSocketCrossfade_float(UnityTexture2D Sockets, float Socket, float FrameA, float LastFrameA, float FrameB,
                                 float LastFrameB, float Blend, out float3 Position, out float4 Rotation)
{
  dqskin_socket_crossfade(Sockets.tex, Socket, FrameA, LastFrameA, FrameB, LastFrameB, Blend, Position, Rotation);
}

void DqskinSocketMatrix_float(UnityTexture2D Sockets, float Socket, float Frame, float LastFrame, out float4x4 Matrix)
{
  float4 r0, r1, r2;
  dqskin_socket_matrix(Sockets.tex, Socket, Frame, LastFrame, r0, r1, r2);
  Matrix = float4x4(r0, r1, r2, float4(0.0, 0.0, 0.0, 1.0));
}

// Half precision graphs call these; the texture math stays in float (texel rows and dual quaternions need it).
void DqskinClipFrame_half(half Time, half FirstFrame, half FrameCount, half Fps, half Loop, out half Frame,
                          out half LastFrame)
{
  float f, l;
  DqskinClipFrame_float(Time, FirstFrame, FrameCount, Fps, Loop, f, l);
  Frame = half(f);
  LastFrame = half(l);
}

void DqskinVat_half(UnityTexture2D Positions, UnityTexture2D Normals, half2 Uv1, half UvFlipped, half Frame,
                    half LastFrame, half RowsPerFrame, out half3 Position, out half3 Normal)
{
  float3 p, n;
  DqskinVat_float(Positions, Normals, Uv1, UvFlipped, Frame, LastFrame, RowsPerFrame, p, n);
  Position = half3(p);
  Normal = half3(n);
}

void DqskinVatCrossfade_half(UnityTexture2D Positions, UnityTexture2D Normals, half2 Uv1, half UvFlipped,
                             half FrameA, half LastFrameA, half FrameB, half LastFrameB, half Blend,
                             half RowsPerFrame, out half3 Position, out half3 Normal)
{
  float3 p, n;
  DqskinVatCrossfade_float(Positions, Normals, Uv1, UvFlipped, FrameA, LastFrameA, FrameB, LastFrameB, Blend,
                           RowsPerFrame, p, n);
  Position = half3(p);
  Normal = half3(n);
}

void DqskinDqSkin_half(UnityTexture2D Bones, half Texels, half4 Joints, half4 Weights, half RowA, half RowB,
                       half Blend, half3 Position, half3 Normal, out half3 SkinnedPosition, out half3 SkinnedNormal)
{
  float3 p, n;
  DqskinDqSkin_float(Bones, Texels, Joints, Weights, RowA, RowB, Blend, Position, Normal, p, n);
  SkinnedPosition = half3(p);
  SkinnedNormal = half3(n);
}

void DqskinMatrixSkin_half(UnityTexture2D Bones, half Texels, half4 Joints, half4 Weights, half RowA, half RowB,
                           half Blend, half3 Position, half3 Normal, out half3 SkinnedPosition,
                           out half3 SkinnedNormal)
{
  float3 p, n;
  DqskinMatrixSkin_float(Bones, Texels, Joints, Weights, RowA, RowB, Blend, Position, Normal, p, n);
  SkinnedPosition = half3(p);
  SkinnedNormal = half3(n);
}

void DqskinDqSkin8_half(UnityTexture2D Bones, half Texels, half4 Joints0, half4 Weights0, half4 Joints1,
                        half4 Weights1, half RowA, half RowB, half Blend, half3 Position, half3 Normal,
                        out half3 SkinnedPosition, out half3 SkinnedNormal)
{
  float3 p, n;
  DqskinDqSkin8_float(Bones, Texels, Joints0, Weights0, Joints1, Weights1, RowA, RowB, Blend, Position, Normal, p, n);
  SkinnedPosition = half3(p);
  SkinnedNormal = half3(n);
}

void DqskinMatrixSkin8_half(UnityTexture2D Bones, half Texels, half4 Joints0, half4 Weights0, half4 Joints1,
                            half4 Weights1, half RowA, half RowB, half Blend, half3 Position, half3 Normal,
                            out half3 SkinnedPosition, out half3 SkinnedNormal)
{
  float3 p, n;
  DqskinMatrixSkin8_float(Bones, Texels, Joints0, Weights0, Joints1, Weights1, RowA, RowB, Blend, Position, Normal,
                          p, n);
  SkinnedPosition = half3(p);
  SkinnedNormal = half3(n);
}

void DqskinSocket_half(UnityTexture2D Sockets, half Socket, half Frame, half LastFrame, out half3 Position,
                       out half4 Rotation)
{
  float3 p;
  float4 r;
  DqskinSocket_float(Sockets, Socket, Frame, LastFrame, p, r);
  Position = half3(p);
  Rotation = half4(r);
}

void DqskinSocketCrossfade_half(UnityTexture2D Sockets, half Socket, half FrameA, half LastFrameA, half FrameB,
                                half LastFrameB, half Blend, out half3 Position, out half4 Rotation)
{
  float3 p;
  float4 r;
  DqskinSocketCrossfade_float(Sockets, Socket, FrameA, LastFrameA, FrameB, LastFrameB, Blend, p, r);
  Position = half3(p);
  Rotation = half4(r);
}

void DqskinSocketMatrix_half(UnityTexture2D Sockets, half Socket, half Frame, half LastFrame, out half4x4 Matrix)
{
  float4x4 m;
  DqskinSocketMatrix_float(Sockets, Socket, Frame, LastFrame, m);
  Matrix = half4x4(m);
}

#endif  // DQSKIN_SHADER_GRAPH_INCLUDED
