#include "gl_functions.hpp"

namespace dqskin::gpu {

std::string Gl::load(const GpuContext& context) {
#define DQSKIN_GL_LOAD(type, name)                                              \
  name = reinterpret_cast<type>(context.proc_address("gl" #name));              \
  if (!name) return "gl" #name;
  DQSKIN_GL_FUNCTIONS(DQSKIN_GL_LOAD)
#undef DQSKIN_GL_LOAD
  return {};
}

}  // namespace dqskin::gpu
