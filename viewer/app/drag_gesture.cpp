// SPDX-License-Identifier: BSD-3-Clause
#include "viewer/app/detail/drag_gesture.h"

#include "viewer/app/detail/object_pick.h"

namespace voxlink::viewer {

Result<bool> DragGesture::update(SceneSession& session, const render::Camera& camera,
                                 const PointerState& pointer, uint32_t width, uint32_t height,
                                 std::optional<size_t> selected) {
  const bool pressed = pointer.left && !wasLeft_;
  wasLeft_ = pointer.left;
  if (active_ && !pointer.left) {  // released: where the cursor was let go counts too
    const Status last =
        session.dragTo(camera, pointer.x - startX_, pointer.y - startY_, double(height)).status();
    session.endDrag();
    active_ = false;
    VOXLINK_RETURN_IF_ERROR(last);
    return false;
  }
  if (!active_ && !pending_ && pressed && pointer.modifier &&
      (session.dynamic() || !session.staticMeshes().empty())) {
    const std::array<double, 2> at = pointer.pressedAt.value_or(std::array{pointer.x, pointer.y});
    startX_ = at[0];
    startY_ = at[1];
    // Moving meshes' boxes first, then the static meshes': the nearest under the cursor.
    std::vector<render::Box> boxes = session.movingBoxes();
    const size_t moving = boxes.size();
    for (const render::Box& b : session.staticBoxes()) boxes.push_back(b);
    std::optional<size_t> target = pickBox(camera, at[0], at[1], width, height, boxes);
    if (target && *target >= moving) {
      const size_t object = session.staticMeshes().at(*target - moving).object;
      VOXLINK_RETURN_IF_ERROR(session.promote(object));
      pending_ = object;
    } else {
      if (!target) target = selected;
      if (target && *target < session.movingCount()) {
        VOXLINK_RETURN_IF_ERROR(session.beginDrag(*target));
        active_ = true;
      }
    }
  }
  if (pending_) {  // the pressed static mesh is being made to move
    if (!pointer.left) {
      pending_.reset();
      return false;
    }
    const std::optional<size_t> index = session.movingIndexOf(*pending_);
    if (!index) return true;
    pending_.reset();
    VOXLINK_RETURN_IF_ERROR(session.beginDrag(*index));
    active_ = true;
  }
  if (!active_) return false;
  VOXLINK_RETURN_IF_ERROR(
      session.dragTo(camera, pointer.x - startX_, pointer.y - startY_, double(height)).status());
  return true;
}

}  // namespace voxlink::viewer
