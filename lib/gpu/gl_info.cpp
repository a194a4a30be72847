#include "gl_info.hpp"

#include <GL/glcorearb.h>

#include <cstdio>

namespace dqskin::gpu {

std::string query_gl(ProcLoader loader, const void* user, GpuContextInfo& info) {
  const auto get_string = reinterpret_cast<PFNGLGETSTRINGPROC>(loader("glGetString", user));
  const auto get_integer = reinterpret_cast<PFNGLGETINTEGERVPROC>(loader("glGetIntegerv", user));
  if (!get_string || !get_integer) return "no glGetString";
  const auto text = [&](GLenum e) {
    const GLubyte* s = get_string(e);
    return s ? std::string(reinterpret_cast<const char*>(s)) : std::string("?");
  };
  info.version = text(GL_VERSION);
  info.renderer = text(GL_RENDERER);
  // Mesa's and Google's software rasterizers name themselves in GL_RENDERER.
  info.hardware = true;
  for (const char* software : {"llvmpipe", "softpipe", "swrast", "SwiftShader"})
    if (info.renderer.find(software) != std::string::npos) info.hardware = false;
  GLint major = 0, minor = 0;
  get_integer(GL_MAJOR_VERSION, &major);
  get_integer(GL_MINOR_VERSION, &minor);
  if (major > 4 || (major == 4 && minor >= 3)) return {};
  return "OpenGL " + info.version + " (" + info.renderer + ")";
}

}  // namespace dqskin::gpu
