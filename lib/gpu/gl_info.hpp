// Reading GL_VERSION / GL_RENDERER and checking the 4.3 core requirement right after a context is made
// current (internal to the backends).
#pragma once

#include "dqskin/gpu_context.hpp"

#include <string>

namespace dqskin::gpu {

using ProcLoader = void* (*)(const char* name, const void* user);

// Fills info.version/renderer through glGetString found with `loader`; returns an empty string when the
// context is at least OpenGL 4.3, else what it offers ("OpenGL 3.1 Mesa ...").
std::string query_gl(ProcLoader loader, const void* user, GpuContextInfo& info);

}  // namespace dqskin::gpu
