// The OpenGL entry points dqskin uses, resolved through the backend's own get-proc-address: one X-macro
// list over Khronos's <GL/glcorearb.h>, so that the library links no libGL/libOpenGL (libepoxy aborts
// under OSMesa on Debian 12, and glad is not packaged). Internal to the GPU code.
#pragma once

#include "dqskin/gpu_context.hpp"

#include <GL/glcorearb.h>

#include <string>

namespace dqskin::gpu {

#define DQSKIN_GL_FUNCTIONS(X)                                          \
  X(PFNGLGETERRORPROC, GetError)                                        \
  X(PFNGLGETINTEGERVPROC, GetIntegerv)                                  \
  X(PFNGLGETINTEGERI_VPROC, GetIntegeri_v)                              \
  X(PFNGLGETSTRINGPROC, GetString)                                      \
  X(PFNGLGETSTRINGIPROC, GetStringi)                                    \
  X(PFNGLFINISHPROC, Finish)                                            \
  X(PFNGLFLUSHPROC, Flush)                                              \
  X(PFNGLCREATESHADERPROC, CreateShader)                                \
  X(PFNGLSHADERSOURCEPROC, ShaderSource)                                \
  X(PFNGLCOMPILESHADERPROC, CompileShader)                              \
  X(PFNGLGETSHADERIVPROC, GetShaderiv)                                  \
  X(PFNGLGETSHADERINFOLOGPROC, GetShaderInfoLog)                        \
  X(PFNGLDELETESHADERPROC, DeleteShader)                                \
  X(PFNGLCREATEPROGRAMPROC, CreateProgram)                              \
  X(PFNGLATTACHSHADERPROC, AttachShader)                                \
  X(PFNGLLINKPROGRAMPROC, LinkProgram)                                  \
  X(PFNGLGETPROGRAMIVPROC, GetProgramiv)                                \
  X(PFNGLGETPROGRAMINFOLOGPROC, GetProgramInfoLog)                      \
  X(PFNGLDELETEPROGRAMPROC, DeleteProgram)                              \
  X(PFNGLUSEPROGRAMPROC, UseProgram)                                    \
  X(PFNGLGETUNIFORMLOCATIONPROC, GetUniformLocation)                    \
  X(PFNGLUNIFORM1IPROC, Uniform1i)                                      \
  X(PFNGLUNIFORM1UIPROC, Uniform1ui)                                    \
  X(PFNGLGENBUFFERSPROC, GenBuffers)                                    \
  X(PFNGLDELETEBUFFERSPROC, DeleteBuffers)                              \
  X(PFNGLBINDBUFFERPROC, BindBuffer)                                    \
  X(PFNGLBINDBUFFERBASEPROC, BindBufferBase)                            \
  X(PFNGLBUFFERDATAPROC, BufferData)                                    \
  X(PFNGLBUFFERSUBDATAPROC, BufferSubData)                              \
  X(PFNGLGETBUFFERSUBDATAPROC, GetBufferSubData)                        \
  X(PFNGLMAPBUFFERRANGEPROC, MapBufferRange)                            \
  X(PFNGLUNMAPBUFFERPROC, UnmapBuffer)                                  \
  X(PFNGLGENTEXTURESPROC, GenTextures)                                  \
  X(PFNGLDELETETEXTURESPROC, DeleteTextures)                            \
  X(PFNGLBINDTEXTUREPROC, BindTexture)                                  \
  X(PFNGLACTIVETEXTUREPROC, ActiveTexture)                              \
  X(PFNGLTEXSTORAGE2DPROC, TexStorage2D)                                \
  X(PFNGLTEXSUBIMAGE2DPROC, TexSubImage2D)                              \
  X(PFNGLTEXPARAMETERIPROC, TexParameteri)                              \
  X(PFNGLDISPATCHCOMPUTEPROC, DispatchCompute)                          \
  X(PFNGLMEMORYBARRIERPROC, MemoryBarrier)                              \
  X(PFNGLFENCESYNCPROC, FenceSync)                                      \
  X(PFNGLCLIENTWAITSYNCPROC, ClientWaitSync)                            \
  X(PFNGLDELETESYNCPROC, DeleteSync)                                    \
  /* rasterization (lib/render) */                                      \
  X(PFNGLGENFRAMEBUFFERSPROC, GenFramebuffers)                          \
  X(PFNGLDELETEFRAMEBUFFERSPROC, DeleteFramebuffers)                    \
  X(PFNGLBINDFRAMEBUFFERPROC, BindFramebuffer)                          \
  X(PFNGLFRAMEBUFFERRENDERBUFFERPROC, FramebufferRenderbuffer)          \
  X(PFNGLCHECKFRAMEBUFFERSTATUSPROC, CheckFramebufferStatus)            \
  X(PFNGLBLITFRAMEBUFFERPROC, BlitFramebuffer)                          \
  X(PFNGLGENRENDERBUFFERSPROC, GenRenderbuffers)                        \
  X(PFNGLDELETERENDERBUFFERSPROC, DeleteRenderbuffers)                  \
  X(PFNGLBINDRENDERBUFFERPROC, BindRenderbuffer)                        \
  X(PFNGLRENDERBUFFERSTORAGEMULTISAMPLEPROC, RenderbufferStorageMultisample)\
  X(PFNGLVIEWPORTPROC, Viewport)                                        \
  X(PFNGLENABLEPROC, Enable)                                            \
  X(PFNGLDISABLEPROC, Disable)                                          \
  X(PFNGLDEPTHFUNCPROC, DepthFunc)                                      \
  X(PFNGLCLEARBUFFERFVPROC, ClearBufferfv)                              \
  X(PFNGLREADBUFFERPROC, ReadBuffer)                                    \
  X(PFNGLREADPIXELSPROC, ReadPixels)                                    \
  X(PFNGLPIXELSTOREIPROC, PixelStorei)                                  \
  X(PFNGLGENVERTEXARRAYSPROC, GenVertexArrays)                          \
  X(PFNGLDELETEVERTEXARRAYSPROC, DeleteVertexArrays)                    \
  X(PFNGLBINDVERTEXARRAYPROC, BindVertexArray)                          \
  X(PFNGLVERTEXATTRIBPOINTERPROC, VertexAttribPointer)                  \
  X(PFNGLENABLEVERTEXATTRIBARRAYPROC, EnableVertexAttribArray)          \
  X(PFNGLDISABLEVERTEXATTRIBARRAYPROC, DisableVertexAttribArray)        \
  X(PFNGLVERTEXATTRIB1FPROC, VertexAttrib1f)                            \
  X(PFNGLVERTEXATTRIB2FPROC, VertexAttrib2f)                            \
  X(PFNGLVERTEXATTRIB3FPROC, VertexAttrib3f)                            \
  X(PFNGLVERTEXATTRIB4FPROC, VertexAttrib4f)                            \
  X(PFNGLGENERATEMIPMAPPROC, GenerateMipmap)                            \
  X(PFNGLBLENDFUNCPROC, BlendFunc)                                      \
  X(PFNGLDEPTHMASKPROC, DepthMask)                                      \
  X(PFNGLDRAWELEMENTSPROC, DrawElements)                                \
  X(PFNGLUNIFORMMATRIX3FVPROC, UniformMatrix3fv)                        \
  X(PFNGLUNIFORMMATRIX4FVPROC, UniformMatrix4fv)                        \
  X(PFNGLUNIFORM1FPROC, Uniform1f)                                      \
  X(PFNGLUNIFORM3FPROC, Uniform3f)                                      \
  X(PFNGLUNIFORM4FPROC, Uniform4f)

// The function table of one context.
struct Gl {
#define DQSKIN_GL_MEMBER(type, name) type name = nullptr;
  DQSKIN_GL_FUNCTIONS(DQSKIN_GL_MEMBER)
#undef DQSKIN_GL_MEMBER

  // OpenGL 4.4 or ARB_buffer_storage: persistently mapped buffers. Null where the context has neither:
  // get-proc-address can return a stub for anything, so the version and the extension list decide (NVIDIA
  // answers a request for 4.3 with exactly 4.3, and offers the extension).
  PFNGLBUFFERSTORAGEPROC BufferStorage = nullptr;

  // Resolves every entry point; returns the name of the first one missing, or empty.
  std::string load(const GpuContext& context);
};

}  // namespace dqskin::gpu
