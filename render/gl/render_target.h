// SPDX-License-Identifier: BSD-3-Clause
// The RGBA32F texture a renderer writes (one texel per pixel, row 0 = top row of the image).
#pragma once

#include <cstdint>

#include "base/error.h"
#include "render/gl/detail/gl_objects.h"
#include "render/image.h"

namespace voxlink::render::gl {

class RenderTarget {
 public:
  // Reallocates when the size changes. Fails (kTooLarge, naming the size and the bytes) when GL
  // cannot allocate the texture: a compute pass into it would run for minutes, then fail.
  Status resize(uint32_t width, uint32_t height);
  uint32_t width() const { return width_; }
  uint32_t height() const { return height_; }
  GLuint texture() const { return texture_.id(); }
  // Reads the texture back (waits for the GPU).
  Image read() const;

 private:
  GlTexture texture_;
  uint32_t width_ = 0, height_ = 0;
};

}  // namespace voxlink::render::gl
