// SPDX-License-Identifier: BSD-3-Clause
// The mouse gesture that drags a moving object of a scene (docs/viewer.md): a modifier + left
// press picks the object under the cursor (else the one selected in the panel) and starts a
// drag; while the button stays down the object follows the cursor in the view plane, clamped
// into the grid; releasing ends it (at the release position). With no moving object under the
// cursor and none selected, a press on a static mesh makes it move first (SceneSession::promote);
// the drag starts once the rebuild is swapped in, from the press, if the button is still down. Free
// of GLFW and ImGui: the window loop feeds it the pointer, tests feed it made-up pointers.
#pragma once

#include <array>
#include <optional>

#include "viewer/app/scene_session.h"

namespace voxlink::viewer {

struct PointerState {
  bool modifier = false;  // Ctrl
  bool left = false;
  double x = 0, y = 0;  // framebuffer pixels, y down
  // Where the left button went down this frame, when known (GlfwWindow::takeLeftPressPosition):
  // the drag starts and picks there rather than at (x, y).
  std::optional<std::array<double, 2>> pressedAt;
};

class DragGesture {
 public:
  // Returns whether an object drag holds the left button now (the camera must not see it).
  // Errors: what SceneSession::dragTo returns (the drag goes on; the pose is kept).
  Result<bool> update(SceneSession& session, const render::Camera& camera,
                      const PointerState& pointer, uint32_t width, uint32_t height,
                      std::optional<size_t> selected);
  bool active() const { return active_; }
  // An object drag, or a press on a static mesh waiting for it to move, holds the left button.
  bool holding() const { return active_ || pending_.has_value(); }

 private:
  bool active_ = false, wasLeft_ = false;
  std::optional<size_t> pending_;  // the scene object being made to move under the press
  double startX_ = 0, startY_ = 0;
};

}  // namespace voxlink::viewer
