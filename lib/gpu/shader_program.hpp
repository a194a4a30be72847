// Compiling and linking the embedded shaders (glsl/), shared by the deformer and the renderer. Errors
// name the shader file and carry the driver's log on one line; line numbers are the file's.
#pragma once

#include "gl_functions.hpp"
#include "shader_sources.hpp"

#include <initializer_list>
#include <string>

namespace dqskin::gpu {

struct ShaderStage {
  GLenum stage;  // GL_COMPUTE_SHADER, GL_VERTEX_SHADER, …
  const ShaderSource& source;
};

// Compiles every stage with `defines` (lines of "#define …\n") after "#version 430" and links them.
// Throws std::runtime_error naming the file (compile) or the files (link).
GLuint build_program(const Gl& gl, std::initializer_list<ShaderStage> stages, const std::string& defines);

}  // namespace dqskin::gpu
