// SPDX-License-Identifier: BSD-3-Clause
// The GPU side of the shadow cache (`--shadow-rays per-voxel`, shaders/shadow_cache.glsl,
// docs/shadows.md): one byte per stored voxel, four to a 32-bit word, read as a buffer texture and
// set through an image with atomicOr. Cleared and filled before a frame whose world light or
// transfer function differs from the last fill's (the light follows the camera): the fill pass
// (shaders/shadow_fill.comp.glsl) walks one shadow ray per visible stored voxel, one work group per
// occupied brick, so it holds the grid cell of every occupied brick.
#pragma once

#include <cstdint>
#include <span>

#include "base/error.h"
#include "render/gl/detail/gl_objects.h"

namespace voxlink::render::gl {

// Image unit the shader sets codes through (unit 0 is the frame's target image).
inline constexpr GLuint kShadowCacheImage = 1;
// Image unit of the marks: one bit per slot, set by the marking frame (shadow_cache.glsl).
inline constexpr GLuint kShadowMarkImage = 2;
// Storage-buffer binding of the occupied bricks' grid cells the fill pass reads.
inline constexpr GLuint kBrickCellsBinding = 60;

class ShadowCacheBuffer {
 public:
  // Room for `voxels` stored voxels (a byte and a mark bit each), read through texture unit
  // `unit`, and the occupied bricks'
  // grid cells (render/brick_lookup.h: occupiedBrickCells). Refuses (kTooLarge) where one buffer
  // texture cannot address the words (GL_MAX_TEXTURE_BUFFER_SIZE), naming the counts.
  static Result<ShadowCacheBuffer> create(uint64_t voxels, GLuint unit,
                                          std::span<const uint32_t> brickCells);

  // Zeroes every code (the GL clears in place, no upload).
  void clear() const;
  // Zeroes every mark.
  void clearMarks() const;
  // Binds the texture the frame reads, the image the fill pass sets and the marks' image.
  void bind() const;
  // Runs the fill pass with the bound program (its uniforms and the file's buffers set): a work
  // group per occupied brick; `depths` per row is the brick size n, or n + 1 with row aprons.
  void fill(GLint occupiedBricksUniform, GLint depthsUniform, uint32_t depths) const;
  uint64_t bytes() const { return bytes_; }
  // Codes set (non-zero), read back from the GPU: the centres the last fills walked (tests,
  // diagnostics; waits for the GL).
  uint64_t countSetCodes() const;

 private:
  GlBuffer buffer_;
  GlTexture texture_;
  GlBuffer marks_;
  GlTexture marksTexture_;
  GlStorageBuffer brickCells_;
  uint64_t bricks_ = 0;
  uint64_t words_ = 0;
  GLuint unit_ = 0;
  uint64_t bytes_ = 0;
};

}  // namespace voxlink::render::gl
