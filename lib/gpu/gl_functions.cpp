#include "gl_functions.hpp"

#include <cstring>

namespace dqskin::gpu {

std::string Gl::load(const GpuContext& context) {
#define DQSKIN_GL_LOAD(type, name)                                              \
  name = reinterpret_cast<type>(context.proc_address("gl" #name));              \
  if (!name) return "gl" #name;
  DQSKIN_GL_FUNCTIONS(DQSKIN_GL_LOAD)
#undef DQSKIN_GL_LOAD
  GLint major = 0, minor = 0, extensions = 0;
  GetIntegerv(GL_MAJOR_VERSION, &major);
  GetIntegerv(GL_MINOR_VERSION, &minor);
  GetIntegerv(GL_NUM_EXTENSIONS, &extensions);
  bool buffer_storage = major > 4 || (major == 4 && minor >= 4);
  for (GLint i = 0; i < extensions && !buffer_storage; ++i) {
    const GLubyte* name = GetStringi(GL_EXTENSIONS, GLuint(i));
    buffer_storage = name && std::strcmp(reinterpret_cast<const char*>(name), "GL_ARB_buffer_storage") == 0;
  }
  if (buffer_storage)
    BufferStorage = reinterpret_cast<PFNGLBUFFERSTORAGEPROC>(context.proc_address("glBufferStorage"));
  return {};
}

}  // namespace dqskin::gpu
