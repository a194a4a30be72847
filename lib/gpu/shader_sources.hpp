// The shaders of glsl/, embedded into the library at build time by glsl/embed.cmake (internal).
#pragma once

namespace dqskin::gpu {

struct ShaderSource {
  const char* file;  // as in the repository, for error messages
  const char* text;
};

extern const ShaderSource kSkinComp;    // glsl/skin.comp
extern const ShaderSource kRenderVert;  // glsl/render.vert
extern const ShaderSource kRenderFrag;  // glsl/render.frag

}  // namespace dqskin::gpu
