// SPDX-License-Identifier: BSD-3-Clause
// Move-only owners of GL buffer and texture names.
#pragma once

#include <epoxy/gl.h>

#include <utility>

namespace voxlink::render::gl {

template <void (*Delete)(GLuint)>
class GlName {
 public:
  GlName() = default;
  explicit GlName(GLuint id) : id_(id) {}
  GlName(GlName&& o) noexcept : id_(std::exchange(o.id_, 0)) {}
  GlName& operator=(GlName&& o) noexcept {
    std::swap(id_, o.id_);
    return *this;
  }
  GlName(const GlName&) = delete;
  GlName& operator=(const GlName&) = delete;
  ~GlName() {
    if (id_) Delete(id_);
  }
  GLuint id() const { return id_; }
  explicit operator bool() const { return id_ != 0; }

 private:
  GLuint id_ = 0;
};

inline void deleteBuffer(GLuint id) { glDeleteBuffers(1, &id); }
inline void deleteTexture(GLuint id) { glDeleteTextures(1, &id); }
inline void deleteFramebuffer(GLuint id) { glDeleteFramebuffers(1, &id); }
using GlBuffer = GlName<deleteBuffer>;
using GlTexture = GlName<deleteTexture>;
using GlFramebuffer = GlName<deleteFramebuffer>;

inline GlBuffer createBuffer() {
  GLuint id = 0;
  glCreateBuffers(1, &id);
  return GlBuffer(id);
}

inline GlTexture createTexture(GLenum target) {
  GLuint id = 0;
  glCreateTextures(target, 1, &id);
  return GlTexture(id);
}

// An immutable buffer with its size.
struct GlStorageBuffer {
  GlBuffer buffer;
  size_t bytes = 0;
};

inline GlStorageBuffer createStorageBuffer(const void* data, size_t bytes) {
  GlStorageBuffer b{createBuffer(), bytes};
  glNamedBufferStorage(b.buffer.id(), GLsizeiptr(bytes), data, 0);
  return b;
}

}  // namespace voxlink::render::gl
