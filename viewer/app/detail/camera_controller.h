// SPDX-License-Identifier: BSD-3-Clause
// Mouse and key input -> camera: orbit (left drag, arrows), pan (right or middle drag, shift +
// left drag, shift + arrows), zoom (wheel, +/-), reset (R). Independent of GLFW so tests can
// drive it with synthetic input.
#pragma once

#include "render/camera.h"

namespace voxlink::viewer {

using render::Camera;

struct InputFrame {
  double mouseX = 0, mouseY = 0;  // pixels, origin top left
  bool left = false, right = false, middle = false, shift = false;
  double scroll = 0;  // wheel steps this frame (+ = away from the user)
  // Keys pressed (or repeating) this frame.
  bool arrowLeft = false, arrowRight = false, arrowUp = false, arrowDown = false;
  bool zoomIn = false, zoomOut = false, reset = false;
};

class CameraController {
 public:
  explicit CameraController(const Camera& home) : home_(home), camera_(home) {}

  // Applies one frame of input for a viewport `height` pixels high; true when the camera moved.
  bool update(const InputFrame& in, double height);
  // A mouse button is held down on the view (the renderer drops its resolution meanwhile).
  bool dragging() const { return dragging_; }
  const Camera& camera() const { return camera_; }
  void reset() { camera_ = home_; }

  static constexpr double kOrbitDegPerPixel = 0.4;
  static constexpr double kKeyOrbitDeg = 5.0;
  static constexpr double kKeyPan = 0.05;  // fraction of the view height
  static constexpr double kZoomPerStep = 1.1;

 private:
  Camera home_;
  Camera camera_;
  bool dragging_ = false;
  double lastX_ = 0, lastY_ = 0;
};

}  // namespace voxlink::viewer
