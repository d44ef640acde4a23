// SPDX-License-Identifier: BSD-3-Clause
// Shows a render target in the window, scaled to the framebuffer (a reduced-resolution frame
// while the user drags fills the window too).
#pragma once

#include "render/gl/render_target.h"
#include "render/gl/shader_program.h"

namespace voxlink::viewer {

using render::gl::ComputeProgram;
using render::gl::GlFramebuffer;
using render::gl::GlTexture;
using render::gl::RenderTarget;

class Display {
 public:
  static Result<Display> create();
  // Draws `target` over the whole default framebuffer.
  void show(const RenderTarget& target, int framebufferWidth, int framebufferHeight);

 private:
  ComputeProgram program_;
  GlTexture texture_;
  GlFramebuffer framebuffer_;
  uint32_t width_ = 0, height_ = 0;
};

}  // namespace voxlink::viewer
