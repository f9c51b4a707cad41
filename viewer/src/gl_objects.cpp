#include "gl_objects.h"

#include <algorithm>
#include <vector>

namespace wirerig::gl {

void DynamicBuffer::Upload(const void* data, std::size_t bytes) {
  glBindBuffer(target_, buffer_.get());
  if (bytes > capacity_) {
    capacity_ = std::max<std::size_t>({bytes, 2 * capacity_, 256});
  }
  // Orphan, then fill: the driver hands out fresh storage if the old one is still in use.
  glBufferData(target_, static_cast<GLsizeiptr>(capacity_), nullptr, GL_STREAM_DRAW);
  if (bytes > 0) glBufferSubData(target_, 0, static_cast<GLsizeiptr>(bytes), data);
}

namespace {

std::string ShaderLog(GLuint shader) {
  GLint length = 0;
  glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
  std::string log(static_cast<std::size_t>(std::max(length, 1)), '\0');
  glGetShaderInfoLog(shader, length, nullptr, log.data());
  while (!log.empty() && (log.back() == '\0' || log.back() == '\n')) log.pop_back();
  return log;
}

std::string ProgramLog(GLuint program) {
  GLint length = 0;
  glGetProgramiv(program, GL_INFO_LOG_LENGTH, &length);
  std::string log(static_cast<std::size_t>(std::max(length, 1)), '\0');
  glGetProgramInfoLog(program, length, nullptr, log.data());
  while (!log.empty() && (log.back() == '\0' || log.back() == '\n')) log.pop_back();
  return log;
}

// Compiles one stage; returns 0 and fills `error` on failure.
GLuint Compile(GLenum stage, std::string_view source, std::string_view program_name,
               std::string_view stage_name, std::string* error) {
  GLuint shader = glCreateShader(stage);
  const char* text = source.data();
  const GLint length = static_cast<GLint>(source.size());
  glShaderSource(shader, 1, &text, &length);
  glCompileShader(shader);
  GLint ok = GL_FALSE;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (ok != GL_TRUE) {
    error->assign("shader program '").append(program_name).append("': the ");
    error->append(stage_name).append(" shader does not compile: ").append(ShaderLog(shader));
    glDeleteShader(shader);
    return 0;
  }
  return shader;
}

}  // namespace

Result<Program> BuildProgram(std::string_view name, std::string_view vertex_source,
                             std::string_view geometry_source, std::string_view fragment_source) {
  std::string error;
  std::vector<GLuint> shaders;
  auto release = [&shaders] {
    for (GLuint s : shaders) glDeleteShader(s);
  };
  struct Stage {
    GLenum type;
    std::string_view source;
    std::string_view name;
  };
  const Stage stages[] = {{GL_VERTEX_SHADER, vertex_source, "vertex"},
                          {GL_GEOMETRY_SHADER, geometry_source, "geometry"},
                          {GL_FRAGMENT_SHADER, fragment_source, "fragment"}};
  for (const Stage& stage : stages) {
    if (stage.source.empty()) continue;
    GLuint shader = Compile(stage.type, stage.source, name, stage.name, &error);
    if (shader == 0) {
      release();
      return Error{error};
    }
    shaders.push_back(shader);
  }
  Program program = Program::Make();
  for (GLuint s : shaders) glAttachShader(program.get(), s);
  glLinkProgram(program.get());
  GLint ok = GL_FALSE;
  glGetProgramiv(program.get(), GL_LINK_STATUS, &ok);
  for (GLuint s : shaders) glDetachShader(program.get(), s);
  release();
  if (ok != GL_TRUE) {
    error.assign("shader program '").append(name).append("' does not link: ");
    error.append(ProgramLog(program.get()));
    return Error{error};
  }
  return program;
}

std::string TakeGlError() {
  std::string first;
  for (int i = 0; i < 16; ++i) {
    const GLenum e = glGetError();
    if (e == GL_NO_ERROR) break;
    if (!first.empty()) continue;
    switch (e) {
      case GL_INVALID_ENUM:
        first = "GL_INVALID_ENUM";
        break;
      case GL_INVALID_VALUE:
        first = "GL_INVALID_VALUE";
        break;
      case GL_INVALID_OPERATION:
        first = "GL_INVALID_OPERATION";
        break;
      case GL_INVALID_FRAMEBUFFER_OPERATION:
        first = "GL_INVALID_FRAMEBUFFER_OPERATION";
        break;
      case GL_OUT_OF_MEMORY:
        first = "GL_OUT_OF_MEMORY";
        break;
      default:
        first = "GL error " + std::to_string(e);
        break;
    }
  }
  return first;
}

}  // namespace wirerig::gl
