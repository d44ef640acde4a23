// SPDX-License-Identifier: BSD-3-Clause
// The GPU side of the per-frame shadow cache (`--shadow-rays per-voxel`, shaders/shadow_cache.glsl,
// docs/shadows.md): one byte per stored voxel, four to a 32-bit word, read as a buffer texture and
// set through an image with atomicOr. Cleared before every frame: the light follows the camera.
#pragma once

#include <cstdint>

#include "base/error.h"
#include "render/gl/detail/gl_objects.h"

namespace voxlink::render::gl {

// Image unit the shader sets codes through (unit 0 is the frame's target image).
inline constexpr GLuint kShadowCacheImage = 1;

class ShadowCacheBuffer {
 public:
  // Room for `voxels` stored voxels, read through texture unit `unit`. Refuses (kTooLarge) where
  // one buffer texture cannot address the words (GL_MAX_TEXTURE_BUFFER_SIZE), naming the counts.
  static Result<ShadowCacheBuffer> create(uint64_t voxels, GLuint unit);

  // Zeroes every code (the GL clears in place, no upload) and binds the texture and the image.
  void clearAndBind() const;
  uint64_t bytes() const { return bytes_; }

 private:
  GlBuffer buffer_;
  GlTexture texture_;
  GLuint unit_ = 0;
  uint64_t bytes_ = 0;
};

}  // namespace voxlink::render::gl
