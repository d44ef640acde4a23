// SPDX-License-Identifier: BSD-3-Clause
#include "viewer/app/detail/display.h"

namespace voxlink::viewer {

using render::gl::ComputeProgram;
using render::gl::createTexture;
using render::gl::GlFramebuffer;
using render::gl::RenderTarget;

Result<Display> Display::create() {
  Display d;
  VOXLINK_ASSIGN_OR_RETURN(d.program_, ComputeProgram::build("display.comp.glsl"));
  GLuint fbo = 0;
  glCreateFramebuffers(1, &fbo);
  d.framebuffer_ = GlFramebuffer(fbo);
  return d;
}

void Display::show(const RenderTarget& target, int framebufferWidth, int framebufferHeight) {
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glViewport(0, 0, framebufferWidth, framebufferHeight);
  glClearColor(0, 0, 0, 1);
  glClear(GL_COLOR_BUFFER_BIT);
  if (!target.texture() || target.width() == 0) return;
  if (!texture_ || width_ != target.width() || height_ != target.height()) {
    texture_ = createTexture(GL_TEXTURE_2D);
    glTextureStorage2D(texture_.id(), 1, GL_RGBA8, GLsizei(target.width()),
                       GLsizei(target.height()));
    glNamedFramebufferTexture(framebuffer_.id(), GL_COLOR_ATTACHMENT0, texture_.id(), 0);
    width_ = target.width();
    height_ = target.height();
  }
  program_.use();
  glBindImageTexture(0, target.texture(), 0, GL_FALSE, 0, GL_READ_ONLY, GL_RGBA32F);
  glBindImageTexture(1, texture_.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA8);
  glDispatchCompute((width_ + 7) / 8, (height_ + 7) / 8, 1);
  glMemoryBarrier(GL_FRAMEBUFFER_BARRIER_BIT);
  glBlitNamedFramebuffer(framebuffer_.id(), 0, 0, 0, GLint(width_), GLint(height_), 0, 0,
                         framebufferWidth, framebufferHeight, GL_COLOR_BUFFER_BIT, GL_LINEAR);
}

}  // namespace voxlink::viewer
