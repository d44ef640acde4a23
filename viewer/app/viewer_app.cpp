// SPDX-License-Identifier: BSD-3-Clause
#include "viewer/app/viewer_app.h"

#include <epoxy/gl.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include <algorithm>
#include <chrono>
#include <cmath>

#include "viewer/app/detail/camera_controller.h"
#include "viewer/app/detail/display.h"
#include "viewer/app/detail/drag_gesture.h"
#include "viewer/app/detail/glfw_window.h"
#include "viewer/app/detail/scene_panel.h"
#include "viewer/app/detail/viewer_state.h"
#include "viewer/app/scene_session.h"

namespace voxlink::viewer {

using render::Camera;
using render::Image;
using render::RenderSettings;
using render::Sampling;
using render::srgbDecode;
using render::writeImage;
using render::gl::RenderTarget;

namespace {

double nowMs() {
  return std::chrono::duration<double, std::milli>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

// Keys with edge detection: pressed this frame.
class Keys {
 public:
  explicit Keys(GLFWwindow* w) : window_(w) {}
  bool pressed(int key) {
    const bool down = glfwGetKey(window_, key) == GLFW_PRESS;
    const bool was = down_[key];
    down_[key] = down;
    return down && !was;
  }
  bool held(int key) const { return glfwGetKey(window_, key) == GLFW_PRESS; }

 private:
  GLFWwindow* window_;
  bool down_[GLFW_KEY_LAST + 1] = {};
};

InputFrame collectInput(GLFWwindow* w, Keys& keys, bool mouseFree, bool keysFree) {
  InputFrame in;
  const ImGuiIO& io = ImGui::GetIO();
  glfwGetCursorPos(w, &in.mouseX, &in.mouseY);
  in.shift = keys.held(GLFW_KEY_LEFT_SHIFT) || keys.held(GLFW_KEY_RIGHT_SHIFT);
  if (mouseFree) {
    in.left = glfwGetMouseButton(w, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS;
    in.right = glfwGetMouseButton(w, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS;
    in.middle = glfwGetMouseButton(w, GLFW_MOUSE_BUTTON_MIDDLE) == GLFW_PRESS;
    in.scroll = io.MouseWheel;
  }
  if (keysFree) {
    in.arrowLeft = keys.held(GLFW_KEY_LEFT);
    in.arrowRight = keys.held(GLFW_KEY_RIGHT);
    in.arrowUp = keys.held(GLFW_KEY_UP);
    in.arrowDown = keys.held(GLFW_KEY_DOWN);
    in.zoomIn = keys.held(GLFW_KEY_EQUAL) || keys.held(GLFW_KEY_KP_ADD);
    in.zoomOut = keys.held(GLFW_KEY_MINUS) || keys.held(GLFW_KEY_KP_SUBTRACT);
    in.reset = keys.pressed(GLFW_KEY_R);
  }
  return in;
}

Status writeScreenshot(ViewerState& s, const Camera& camera, uint32_t w, uint32_t h,
                       const std::string& path) {
  RenderSettings full = s.settings;
  full.width = w;
  full.height = h;
  RenderTarget target;
  VOXLINK_RETURN_IF_ERROR(s.renderer->render(camera, full, target));
  VOXLINK_RETURN_IF_ERROR(writeImage(target.read(), path));
  s.message = "screenshot " + path + cat(" (", w, "x", h, ")");
  return Status::ok();
}

// The window's back buffer as drawn (panels included), top row first.
Status captureWindow(int w, int h, const std::string& path) {
  Image image{uint32_t(w), uint32_t(h)};
  std::vector<uint8_t> rgba(size_t(w) * h * 4);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glReadBuffer(GL_BACK);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < 4; ++c)  // the framebuffer holds sRGB-encoded bytes
        image.pixel(x, y)[c] =
            c == 3 ? 1.0f : float(srgbDecode(rgba[(size_t(h - 1 - y) * w + x) * 4 + c] / 255.0));
  return writeImage(image, path);
}

}  // namespace

Status runViewer(const ViewerOptions& options) {
  VOXLINK_ASSIGN_OR_RETURN(
      auto window,
      GlfwWindow::create(options.windowWidth, options.windowHeight, "VoxLink - " + options.path));
  const std::string glDescription = window->description();
  ViewerState state;
  state.settings = options.settings;
  if (options.tf) state.tf = *options.tf;
  SceneSession* scene = options.scene.get();
  // The session's GL objects go while the window's context lives, however this returns.
  struct DetachOnExit {
    SceneSession* session;
    ~DetachOnExit() {
      if (session) session->detach();
    }
  } detachOnExit{scene};
  if (scene) {
    VOXLINK_RETURN_IF_ERROR(scene->attach());
    if (options.sceneTime) {
      scene->setTime(*options.sceneTime);
      scene->clock().setPlaying(false);
    }
    VOXLINK_RETURN_IF_ERROR(
        state.load(scene->volumeFile(), options.tf.has_value(), scene->renderer()));
    state.shownPath = options.path;
  } else {
    VOXLINK_RETURN_IF_ERROR(state.load(options.path, options.tf.has_value()));
  }
  VOXLINK_ASSIGN_OR_RETURN(Display display, Display::create());
  CameraController controller(
      Camera::framing(state.renderer->geometry().worldBox(), options.camera));

  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini in the user's working directory
  ImGui::StyleColorsDark();
  ImGui_ImplGlfw_InitForOpenGL(window->handle(), true);
  ImGui_ImplOpenGL3_Init("#version 450");

  Keys keys(window->handle());
  RenderTarget target;
  bool dirty = true, showUi = true;
  int frame = 0, screenshots = 0;
  std::array<int, 2> lastSize{0, 0};
  DragGesture drag;
  std::optional<size_t> selected;
  double lastFrameMs = nowMs();
  Status result;
  while (!window->shouldClose()) {
    glfwPollEvents();
    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
    const ImGuiIO& io = ImGui::GetIO();
    const auto size = window->framebufferSize();
    if (size != lastSize) dirty = true;
    lastSize = size;
    const bool keysFree = !io.WantCaptureKeyboard;
    InputFrame input = collectInput(window->handle(), keys, !io.WantCaptureMouse, keysFree);
    // Ctrl + left drag moves a scene's moving object; the camera does not see that button then.
    bool objectMoving = false;
    // A scene with a moving mesh, or a static mesh that can be made to move.
    const bool sceneMoves = scene && (scene->moves() || !scene->staticObjects().empty());
    if (sceneMoves && size[0] > 0 && size[1] > 0) {
      int windowWidth = 0, windowHeight = 0;
      glfwGetWindowSize(window->handle(), &windowWidth, &windowHeight);
      const double toPixels = windowWidth > 0 ? double(size[0]) / windowWidth : 1.0;
      PointerState pointer;
      pointer.modifier = keys.held(GLFW_KEY_LEFT_CONTROL) || keys.held(GLFW_KEY_RIGHT_CONTROL);
      // A drag goes on over the panels; a press there does not start one.
      pointer.left = drag.holding() ? glfwGetMouseButton(window->handle(),
                                                         GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS
                                    : input.left;
      pointer.x = input.mouseX * toPixels;
      pointer.y = input.mouseY * toPixels;
      // The cursor may have moved on since the press within this frame: start where it was.
      if (const auto at = window->takeLeftPressPosition())
        pointer.pressedAt = std::array{(*at)[0] * toPixels, (*at)[1] * toPixels};
      auto dragging = drag.update(*scene, controller.camera(), pointer, uint32_t(size[0]),
                                  uint32_t(size[1]), selected);
      if (!dragging) state.message = dragging.message();
      objectMoving = drag.active();
      if (drag.holding() || pointer.modifier) input.left = false;
      const double now = nowMs();
      auto updated = scene->update((now - lastFrameMs) / 1000.0);
      lastFrameMs = now;
      if (scene->takeRebuilt()) {  // a static mesh now moves: the new static part and renderer
        // The user's transfer function (edited or given) stays: only one object left the file.
        Status loaded = state.load(scene->volumeFile(), true, scene->renderer());
        if (!loaded) state.message = loaded.message();
        selected.reset();  // the moving meshes are numbered anew
        dirty = true;
      }
      if (!updated) {
        state.message = updated.message();
      } else if (*updated) {
        dirty = true;
        objectMoving = true;
      }
    }
    const bool moved = controller.update(input, std::max(size[1], 1));
    if (keysFree) {
      if (keys.pressed(GLFW_KEY_ESCAPE) || keys.pressed(GLFW_KEY_Q)) window->requestClose();
      if (keys.pressed(GLFW_KEY_H)) showUi = !showUi;
      if (keys.pressed(GLFW_KEY_V)) {
        state.settings.sampling =
            state.settings.sampling == Sampling::kVoxel ? Sampling::kTrilinear : Sampling::kVoxel;
        dirty = true;
      }
      if (keys.pressed(GLFW_KEY_P) || keys.pressed(GLFW_KEY_F12)) {
        const std::string path = cat("voxlink-screenshot-", ++screenshots, ".png");
        if (Status s = writeScreenshot(state, controller.camera(), size[0], size[1], path); !s)
          state.message = s.message();
      }
    }
    bool tfDragging = false;
    if (showUi) {
      ImGui::SetNextWindowPos(ImVec2(10, 10), ImGuiCond_FirstUseEver);
      ImGui::SetNextWindowSize(ImVec2(480, 0), ImGuiCond_FirstUseEver);
      ImGui::Begin("VoxLink");
      drawStatsPanel(state, glDescription, state.lastFrameReduced ? target.width() : size[0],
                     state.lastFrameReduced ? target.height() : size[1]);
      if (sceneMoves && ImGui::CollapsingHeader("Moving objects", ImGuiTreeNodeFlags_DefaultOpen))
        dirty |= drawScenePanel(*scene, selected, state.message);
      if (ImGui::CollapsingHeader("Rendering")) dirty |= drawSettingsPanel(state);
      if (ImGui::CollapsingHeader("Transfer function", ImGuiTreeNodeFlags_DefaultOpen)) {
        const bool changed = drawTransferFunctionPanel(state);
        dirty |= changed;
        tfDragging = changed && ImGui::IsMouseDown(ImGuiMouseButton_Left);
      }
      ImGui::End();
    }
    // A finished re-classification: reload the new file with the same view and TF.
    if (auto done = state.reclassifier.takeResult()) {
      if (*done) {
        const std::string path = done->value();
        Status loaded = state.load(path, true);
        state.message = loaded ? "reloaded " + path : loaded.message();
        dirty = true;
      } else {
        state.message = "re-classification failed: " + done->message();
      }
    }

    // Reduced resolution while anything moves, full resolution once it is still.
    const bool interacting = controller.dragging() || moved || tfDragging || objectMoving;
    if (size[0] > 0 && size[1] > 0 && (interacting || dirty || state.lastFrameReduced)) {
      const double scale = interacting ? state.interactiveScale : 1.0;
      state.settings.width = std::max(1u, uint32_t(std::lround(size[0] * scale)));
      state.settings.height = std::max(1u, uint32_t(std::lround(size[1] * scale)));
      const double start = nowMs();
      const uint64_t fills = state.renderer->shadowFills();
      if (Status s = state.renderer->render(controller.camera(), state.settings, target); !s) {
        state.message = s.message();
      } else {
        glFinish();
        state.lastRenderMs = nowMs() - start;
      }
      state.lastFrameFilledShadows = state.renderer->shadowFills() != fills;
      state.lastFrameReduced = interacting;
      dirty = false;
    }
    display.show(target, size[0], size[1]);
    ImGui::Render();
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
    const bool last = options.maxFrames > 0 && ++frame >= options.maxFrames;
    if (last && !options.windowCaptureOnExit.empty())
      result = captureWindow(size[0], size[1], options.windowCaptureOnExit);
    window->swapBuffers();
    if (last) {
      if (!options.screenshotOnExit.empty() && result)
        result =
            writeScreenshot(state, controller.camera(), size[0], size[1], options.screenshotOnExit);
      window->requestClose();
    }
  }
  ImGui_ImplOpenGL3_Shutdown();
  ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext();
  return result;
}

}  // namespace voxlink::viewer
