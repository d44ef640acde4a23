// SPDX-License-Identifier: BSD-3-Clause
// An OpenGL 4.5 core context made current on the calling thread: headless through EGL (no X
// server; what `voxlink render`, the benchmark and the tests use) or a GLFW window (the
// interactive viewer, viewer/app/detail/glfw_window.h). Function pointers come from libepoxy.
#pragma once

#include <memory>
#include <string>

#include "base/error.h"

namespace voxlink::render::gl {

class GlContext {
 public:
  virtual ~GlContext() = default;
  virtual void makeCurrent() = 0;
  // "llvmpipe (LLVM 15.0.6, 256 bits) | 4.5 (Core Profile) Mesa 22.3.6"
  std::string description() const;
};

// EGL without a window system: EGL_PLATFORM_SURFACELESS_MESA, then EGL_PLATFORM_DEVICE_EXT,
// then the default display. The context has no surface: renderers draw into textures.
Result<std::unique_ptr<GlContext>> createHeadlessContext();

// Fails unless the current context offers compute shaders and storage buffers (GL 4.3+).
Status checkGlCapabilities();

}  // namespace voxlink::render::gl
