// SPDX-License-Identifier: BSD-3-Clause
// The interactive viewer's window: GLFW with an OpenGL 4.5 core context (needs an X server or
// Xvfb; headless rendering uses EGL instead, see render/gl/gl_context.h).
#pragma once

#include <array>
#include <memory>
#include <optional>
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
  // Where the cursor was (window coordinates) when the left button last went down, in event
  // order: the polled position may already be further on when a frame sees the press. Once.
  std::optional<std::array<double, 2>> takeLeftPressPosition();

 private:
  explicit GlfwWindow(GLFWwindow* w) : window_(w) {}
  static void onCursor(GLFWwindow* w, double x, double y);
  static void onButton(GLFWwindow* w, int button, int action, int mods);
  GLFWwindow* window_;
  std::array<double, 2> cursor_{0, 0};
  std::optional<std::array<double, 2>> leftPress_;
};

}  // namespace voxlink::viewer
