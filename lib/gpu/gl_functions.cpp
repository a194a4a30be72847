#include "gl_functions.hpp"

namespace dqskin::gpu {

std::string Gl::load(const GpuContext& context) {
#define DQSKIN_GL_LOAD(type, name)                                              \
  name = reinterpret_cast<type>(context.proc_address("gl" #name));              \
  if (!name) return "gl" #name;
  DQSKIN_GL_FUNCTIONS(DQSKIN_GL_LOAD)
#undef DQSKIN_GL_LOAD
  GLint major = 0, minor = 0;
  GetIntegerv(GL_MAJOR_VERSION, &major);
  GetIntegerv(GL_MINOR_VERSION, &minor);
  if (major > 4 || (major == 4 && minor >= 4))
    BufferStorage = reinterpret_cast<PFNGLBUFFERSTORAGEPROC>(context.proc_address("glBufferStorage"));
  return {};
}

}  // namespace dqskin::gpu
