#include "shader_program.hpp"

#include <stdexcept>
#include <vector>

namespace dqskin::gpu {
namespace {

// One line from a multi-line driver log.
std::string one_line(std::string log) {
  for (char& c : log)
    if (c == '\n') c = ' ';
  while (!log.empty() && log.back() == ' ') log.pop_back();
  return log;
}

GLuint compile(const Gl& gl, const ShaderStage& s, const std::string& defines) {
  const std::string header = "#version 430\n" + defines + "#line 1\n";  // the driver's line numbers are the file's
  const char* parts[] = {header.c_str(), s.source.text};
  const GLuint shader = gl.CreateShader(s.stage);
  gl.ShaderSource(shader, 2, parts, nullptr);
  gl.CompileShader(shader);
  GLint ok = 0;
  gl.GetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[4096] = {};
    gl.GetShaderInfoLog(shader, sizeof log, nullptr, log);
    gl.DeleteShader(shader);
    throw std::runtime_error(std::string(s.source.file) + ": compile error: " + one_line(log));
  }
  return shader;
}

}  // namespace

GLuint build_program(const Gl& gl, std::initializer_list<ShaderStage> stages, const std::string& defines) {
  std::vector<GLuint> shaders;
  std::string files;
  try {
    for (const ShaderStage& s : stages) {
      shaders.push_back(compile(gl, s, defines));
      files += (files.empty() ? "" : " + ") + std::string(s.source.file);
    }
  } catch (...) {
    for (GLuint shader : shaders) gl.DeleteShader(shader);
    throw;
  }
  const GLuint program = gl.CreateProgram();
  for (GLuint shader : shaders) gl.AttachShader(program, shader);
  gl.LinkProgram(program);
  for (GLuint shader : shaders) gl.DeleteShader(shader);
  GLint ok = 0;
  gl.GetProgramiv(program, GL_LINK_STATUS, &ok);
  if (!ok) {
    char log[4096] = {};
    gl.GetProgramInfoLog(program, sizeof log, nullptr, log);
    gl.DeleteProgram(program);
    throw std::runtime_error(files + ": link error: " + one_line(log));
  }
  return program;
}

}  // namespace dqskin::gpu
