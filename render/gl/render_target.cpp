// SPDX-License-Identifier: BSD-3-Clause
#include "render/gl/render_target.h"

#include "render/gl/detail/gl_allocation.h"

namespace voxlink::render::gl {

Status RenderTarget::resize(uint32_t width, uint32_t height) {
  if (texture_ && width == width_ && height == height_) return Status::ok();
  discardPendingGlErrors();
  texture_ = createTexture(GL_TEXTURE_2D);
  glTextureStorage2D(texture_.id(), 1, GL_RGBA32F, GLsizei(width), GLsizei(height));
  if (Status s =
          checkGlAllocation(cat("the ", width, "x", height, " image"),
                            cat("RGBA32F, ", uint64_t{width} * height * 16 / 1000000, " MB; "));
      !s) {
    texture_ = GlTexture();
    width_ = height_ = 0;
    return s;
  }
  glTextureParameteri(texture_.id(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTextureParameteri(texture_.id(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  width_ = width;
  height_ = height;
  return Status::ok();
}

Image RenderTarget::read() const {
  Image image(width_, height_);
  if (!texture_) return image;
  glGetTextureImage(texture_.id(), 0, GL_RGBA, GL_FLOAT, GLsizei(image.rgba.size() * sizeof(float)),
                    image.rgba.data());
  return image;
}

}  // namespace voxlink::render::gl
