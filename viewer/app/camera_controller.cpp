// SPDX-License-Identifier: BSD-3-Clause
#include "viewer/app/detail/camera_controller.h"

#include <cmath>

namespace voxlink::viewer {

bool CameraController::update(const InputFrame& in, double height) {
  bool moved = false;
  const bool anyButton = in.left || in.right || in.middle;
  if (anyButton && dragging_) {
    const double dx = in.mouseX - lastX_, dy = in.mouseY - lastY_;
    if (dx != 0 || dy != 0) {
      if (in.right || in.middle || (in.left && in.shift))
        camera_.pan(dx / std::max(height, 1.0), dy / std::max(height, 1.0));
      else
        camera_.orbit(-dx * kOrbitDegPerPixel, dy * kOrbitDegPerPixel);
      moved = true;
    }
  }
  dragging_ = anyButton;
  lastX_ = in.mouseX;
  lastY_ = in.mouseY;
  if (in.scroll != 0) {
    camera_.zoom(std::pow(kZoomPerStep, in.scroll));
    moved = true;
  }
  const double h = (in.arrowRight ? 1.0 : 0.0) - (in.arrowLeft ? 1.0 : 0.0);
  const double v = (in.arrowUp ? 1.0 : 0.0) - (in.arrowDown ? 1.0 : 0.0);
  if (h != 0 || v != 0) {
    if (in.shift)
      camera_.pan(-h * kKeyPan, v * kKeyPan);
    else
      camera_.orbit(-h * kKeyOrbitDeg, v * kKeyOrbitDeg);
    moved = true;
  }
  if (in.zoomIn != in.zoomOut) {
    camera_.zoom(in.zoomIn ? kZoomPerStep : 1.0 / kZoomPerStep);
    moved = true;
  }
  if (in.reset) {
    camera_ = home_;
    moved = true;
  }
  return moved;
}

}  // namespace voxlink::viewer
