// SPDX-License-Identifier: BSD-3-Clause
#include "render/gl/detail/shadow_cache_buffer.h"

#include <algorithm>

namespace voxlink::render::gl {

Result<ShadowCacheBuffer> ShadowCacheBuffer::create(uint64_t voxels, GLuint unit) {
  const uint64_t words = std::max<uint64_t>((voxels + 3) / 4, 1);
  GLint maxTexels = 0;
  glGetIntegerv(GL_MAX_TEXTURE_BUFFER_SIZE, &maxTexels);
  if (words > uint64_t(maxTexels))
    return makeError(ErrorCode::kTooLarge, "shadow cache: ", voxels, " stored voxels need ", words,
                     " words, above the ", maxTexels,
                     " texels one buffer texture addresses here; use --shadow-rays per-sample");
  ShadowCacheBuffer c;
  c.buffer_ = createBuffer();
  c.bytes_ = words * 4;
  glNamedBufferStorage(c.buffer_.id(), GLsizeiptr(c.bytes_), nullptr, 0);
  c.texture_ = createTexture(GL_TEXTURE_BUFFER);
  glTextureBuffer(c.texture_.id(), GL_R32UI, c.buffer_.id());
  c.unit_ = unit;
  if (glGetError() != GL_NO_ERROR)
    return makeError(ErrorCode::kTooLarge, "shadow cache: the GL refused a buffer of ", c.bytes_,
                     " bytes for ", voxels, " stored voxels; use --shadow-rays per-sample");
  return c;
}

void ShadowCacheBuffer::clearAndBind() const {
  // The last frame's image atomics land before the clear (which a later dispatch sees as is).
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  glClearNamedBufferData(buffer_.id(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, nullptr);
  glBindTextureUnit(unit_, texture_.id());
  glBindImageTexture(kShadowCacheImage, texture_.id(), 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32UI);
}

}  // namespace voxlink::render::gl
