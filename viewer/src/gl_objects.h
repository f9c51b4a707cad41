// Small RAII owners of OpenGL objects. Each owns one name, deletes it in its destructor, and
// is movable but not copyable. They must be destroyed while their context is current.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <utility>

#include "gl.h"
#include "wirerig/io/result.h"

namespace wirerig::gl {

template <typename Traits>
class Handle {
 public:
  Handle() = default;
  static Handle Make() {
    Handle handle;
    handle.id_ = Traits::Create();
    return handle;
  }
  ~Handle() { Reset(); }
  Handle(Handle&& other) noexcept : id_(std::exchange(other.id_, 0)) {}
  Handle& operator=(Handle&& other) noexcept {
    if (this != &other) {
      Reset();
      id_ = std::exchange(other.id_, 0);
    }
    return *this;
  }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;

  GLuint get() const { return id_; }
  explicit operator bool() const { return id_ != 0; }
  void Reset() {
    if (id_ != 0) Traits::Destroy(id_);
    id_ = 0;
  }

 private:
  GLuint id_ = 0;
};

struct BufferTraits {
  static GLuint Create() {
    GLuint id = 0;
    glGenBuffers(1, &id);
    return id;
  }
  static void Destroy(GLuint id) { glDeleteBuffers(1, &id); }
};
struct VertexArrayTraits {
  static GLuint Create() {
    GLuint id = 0;
    glGenVertexArrays(1, &id);
    return id;
  }
  static void Destroy(GLuint id) { glDeleteVertexArrays(1, &id); }
};
struct TextureTraits {
  static GLuint Create() {
    GLuint id = 0;
    glGenTextures(1, &id);
    return id;
  }
  static void Destroy(GLuint id) { glDeleteTextures(1, &id); }
};
struct FramebufferTraits {
  static GLuint Create() {
    GLuint id = 0;
    glGenFramebuffers(1, &id);
    return id;
  }
  static void Destroy(GLuint id) { glDeleteFramebuffers(1, &id); }
};
struct RenderbufferTraits {
  static GLuint Create() {
    GLuint id = 0;
    glGenRenderbuffers(1, &id);
    return id;
  }
  static void Destroy(GLuint id) { glDeleteRenderbuffers(1, &id); }
};
struct ProgramTraits {
  static GLuint Create() { return glCreateProgram(); }
  static void Destroy(GLuint id) { glDeleteProgram(id); }
};

using Buffer = Handle<BufferTraits>;
using VertexArray = Handle<VertexArrayTraits>;
using Texture = Handle<TextureTraits>;
using Framebuffer = Handle<FramebufferTraits>;
using Renderbuffer = Handle<RenderbufferTraits>;
using Program = Handle<ProgramTraits>;

// A buffer refilled every frame. Upload() orphans the old storage (glBufferData with null, so
// the driver need not wait for draws still reading it) and copies the new bytes with
// glBufferSubData. Capacity grows geometrically and never shrinks, so the steady state makes
// no allocation.
class DynamicBuffer {
 public:
  explicit DynamicBuffer(GLenum target) : target_(target), buffer_(Buffer::Make()) {}
  // Binds the buffer to its target and uploads `bytes` bytes (may be 0).
  void Upload(const void* data, std::size_t bytes);
  void Bind() const { glBindBuffer(target_, buffer_.get()); }
  GLuint get() const { return buffer_.get(); }
  std::size_t capacity() const { return capacity_; }

 private:
  GLenum target_;
  Buffer buffer_;
  std::size_t capacity_ = 0;
};

// Compiles and links a program from vertex, optional geometry and fragment sources. The error
// names the program and includes the driver's log.
Result<Program> BuildProgram(std::string_view name, std::string_view vertex_source,
                             std::string_view geometry_source, std::string_view fragment_source);

// The first pending GL error as text ("GL_INVALID_OPERATION"), or empty; clears all pending.
std::string TakeGlError();

}  // namespace wirerig::gl
