// SPDX-License-Identifier: BSD-3-Clause
#include "render/gl/detail/shadow_cache_buffer.h"

#include <algorithm>
#include <vector>

namespace voxlink::render::gl {

Result<ShadowCacheBuffer> ShadowCacheBuffer::create(uint64_t voxels, GLuint unit,
                                                    std::span<const uint32_t> brickCells) {
  const uint64_t words = std::max<uint64_t>((voxels + 3) / 4, 1);
  GLint maxTexels = 0;
  glGetIntegerv(GL_MAX_TEXTURE_BUFFER_SIZE, &maxTexels);
  if (words > uint64_t(maxTexels))
    return makeError(ErrorCode::kTooLarge, "shadow cache: ", voxels, " stored voxels need ", words,
                     " words, above the ", maxTexels,
                     " texels one buffer texture addresses here; use --shadow-rays per-sample");
  ShadowCacheBuffer c;
  c.buffer_ = createBuffer();
  glNamedBufferStorage(c.buffer_.id(), GLsizeiptr(words * 4), nullptr, 0);
  c.texture_ = createTexture(GL_TEXTURE_BUFFER);
  glTextureBuffer(c.texture_.id(), GL_R32UI, c.buffer_.id());
  const uint64_t markWords = std::max<uint64_t>((voxels + 31) / 32, 1);
  c.marks_ = createBuffer();
  glNamedBufferStorage(c.marks_.id(), GLsizeiptr(markWords * 4), nullptr, 0);
  c.marksTexture_ = createTexture(GL_TEXTURE_BUFFER);
  glTextureBuffer(c.marksTexture_.id(), GL_R32UI, c.marks_.id());
  // A storage buffer may not be empty.
  const uint32_t none[3] = {0, 0, 0};
  c.brickCells_ = brickCells.empty()
                      ? createStorageBuffer(none, sizeof(none))
                      : createStorageBuffer(brickCells.data(), brickCells.size_bytes());
  c.bricks_ = brickCells.size() / 3;
  c.words_ = words;
  c.unit_ = unit;
  c.bytes_ = words * 4 + markWords * 4 + c.brickCells_.bytes;
  if (glGetError() != GL_NO_ERROR)
    return makeError(ErrorCode::kTooLarge, "shadow cache: the GL refused a buffer of ", c.bytes_,
                     " bytes for ", voxels, " stored voxels; use --shadow-rays per-sample");
  return c;
}

void ShadowCacheBuffer::clear() const {
  // The last fill's image atomics land before the clear (which a later dispatch sees as is).
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  glClearNamedBufferData(buffer_.id(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, nullptr);
}

void ShadowCacheBuffer::clearMarks() const {
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  glClearNamedBufferData(marks_.id(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, nullptr);
}

uint64_t ShadowCacheBuffer::countSetCodes() const {
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);  // the fill's image atomics land first
  std::vector<uint32_t> words(words_);
  glGetNamedBufferSubData(buffer_.id(), 0, GLsizeiptr(words_ * 4), words.data());
  uint64_t set = 0;
  for (uint32_t w : words)
    for (int b = 0; b < 4; ++b) set += ((w >> (8 * b)) & 0xFFu) != 0;
  return set;
}

void ShadowCacheBuffer::bind() const {
  glBindTextureUnit(unit_, texture_.id());
  glBindImageTexture(kShadowCacheImage, texture_.id(), 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32UI);
  glBindImageTexture(kShadowMarkImage, marksTexture_.id(), 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32UI);
}

void ShadowCacheBuffer::fill(GLint occupiedBricksUniform, GLint depthsUniform,
                             uint32_t depths) const {
  if (bricks_ == 0) return;
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kBrickCellsBinding, brickCells_.buffer.id());
  glUniform1ui(occupiedBricksUniform, GLuint(bricks_));
  glUniform1ui(depthsUniform, depths);
  // GL guarantees 65535 work groups per dimension: bricks beyond fill further rows of y.
  const uint64_t x = std::min<uint64_t>(bricks_, 65535);
  const uint64_t y = (bricks_ + x - 1) / x;
  glDispatchCompute(GLuint(x), GLuint(y), 1);
  // The frame reads the codes through a buffer texture.
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
}

}  // namespace voxlink::render::gl
