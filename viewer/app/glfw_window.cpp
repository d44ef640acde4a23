// SPDX-License-Identifier: BSD-3-Clause
#include "viewer/app/detail/glfw_window.h"

#include <epoxy/gl.h>
// GLFW after epoxy, without its own GL header.
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <array>
#include <utility>

namespace voxlink::viewer {

using render::gl::checkGlCapabilities;

namespace {

std::string lastGlfwError() {
  const char* description = nullptr;
  glfwGetError(&description);
  return description ? description : "unknown error";
}

}  // namespace

Result<std::unique_ptr<GlfwWindow>> GlfwWindow::create(int width, int height,
                                                       const std::string& title) {
  if (!glfwInit())
    return makeError(
        ErrorCode::kUnsupported, "GLFW: cannot initialize (", lastGlfwError(),
        "); the interactive viewer needs a display (try xvfb-run -a), `voxlink render` does not");
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  GLFWwindow* w = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
  if (!w) {
    const std::string error = lastGlfwError();
    glfwTerminate();
    return makeError(ErrorCode::kUnsupported, "GLFW: no OpenGL 4.5 core window: ", error);
  }
  glfwMakeContextCurrent(w);
  glfwSwapInterval(0);  // llvmpipe frames are slow enough; never wait for a vertical retrace
  std::unique_ptr<GlfwWindow> window(new GlfwWindow(w));
  // Installed before ImGui's backend, which chains them.
  glfwSetWindowUserPointer(w, window.get());
  glfwGetCursorPos(w, &window->cursor_[0], &window->cursor_[1]);
  glfwSetCursorPosCallback(w, &GlfwWindow::onCursor);
  glfwSetMouseButtonCallback(w, &GlfwWindow::onButton);
  VOXLINK_RETURN_IF_ERROR(checkGlCapabilities());
  return window;
}

GlfwWindow::~GlfwWindow() {
  glfwDestroyWindow(window_);
  glfwTerminate();
}

void GlfwWindow::makeCurrent() { glfwMakeContextCurrent(window_); }
bool GlfwWindow::shouldClose() const { return glfwWindowShouldClose(window_); }
void GlfwWindow::requestClose() { glfwSetWindowShouldClose(window_, GLFW_TRUE); }
void GlfwWindow::swapBuffers() { glfwSwapBuffers(window_); }

void GlfwWindow::onCursor(GLFWwindow* w, double x, double y) {
  static_cast<GlfwWindow*>(glfwGetWindowUserPointer(w))->cursor_ = {x, y};
}

void GlfwWindow::onButton(GLFWwindow* w, int button, int action, int) {
  auto* self = static_cast<GlfwWindow*>(glfwGetWindowUserPointer(w));
  if (button == GLFW_MOUSE_BUTTON_LEFT && action == GLFW_PRESS) self->leftPress_ = self->cursor_;
}

std::optional<std::array<double, 2>> GlfwWindow::takeLeftPressPosition() {
  return std::exchange(leftPress_, std::nullopt);
}

std::array<int, 2> GlfwWindow::framebufferSize() const {
  std::array<int, 2> size{0, 0};
  glfwGetFramebufferSize(window_, &size[0], &size[1]);
  return size;
}

}  // namespace voxlink::viewer
