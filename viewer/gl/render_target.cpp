#include "viewer/gl/render_target.h"

namespace voxlink::viewer {

void RenderTarget::resize(uint32_t width, uint32_t height) {
  if (texture_ && width == width_ && height == height_) return;
  texture_ = createTexture(GL_TEXTURE_2D);
  glTextureStorage2D(texture_.id(), 1, GL_RGBA32F, GLsizei(width), GLsizei(height));
  glTextureParameteri(texture_.id(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTextureParameteri(texture_.id(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  width_ = width;
  height_ = height;
}

Image RenderTarget::read() const {
  Image image(width_, height_);
  if (!texture_) return image;
  glGetTextureImage(texture_.id(), 0, GL_RGBA, GL_FLOAT, GLsizei(image.rgba.size() * sizeof(float)),
                    image.rgba.data());
  return image;
}

}  // namespace voxlink::viewer
