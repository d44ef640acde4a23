// SPDX-License-Identifier: BSD-3-Clause
// The interactive viewer's window: GLFW with an OpenGL 4.5 core context (needs an X server or
// Xvfb; headless rendering uses EGL instead, see render/gl/gl_context.h).
#pragma once

#include <memory>
#include <string>

#include "render/gl/gl_context.h"

struct GLFWwindow;

namespace voxlink::viewer {

using render::gl::GlContext;

class GlfwWindow : public GlContext {
 public:
  static Result<std::unique_ptr<GlfwWindow>> create(int width, int height,
                                                    const std::string& title);
  ~GlfwWindow() override;
  void makeCurrent() override;
  GLFWwindow* handle() const { return window_; }
  bool shouldClose() const;
  void requestClose();
  void swapBuffers();
  // Framebuffer size in pixels (may differ from the window size on scaled displays).
  std::array<int, 2> framebufferSize() const;

 private:
  explicit GlfwWindow(GLFWwindow* w) : window_(w) {}
  GLFWwindow* window_;
};

}  // namespace voxlink::viewer
