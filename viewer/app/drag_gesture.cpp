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
      (session.dynamic() || !session.staticObjects().empty())) {
    const std::array<double, 2> at = pointer.pressedAt.value_or(std::array{pointer.x, pointer.y});
    startX_ = at[0];
    startY_ = at[1];
    // A moving mesh under the cursor (its box), else the one selected in the panel (dragged
    // from anywhere, as before static meshes could move), else a static mesh under the cursor,
    // which is made to move.
    std::optional<size_t> target =
        pickBox(camera, at[0], at[1], width, height, session.movingBoxes());
    if (!target) target = selected;
    if (target && *target < session.movingCount()) {
      VOXLINK_RETURN_IF_ERROR(session.beginDrag(*target));
      active_ = true;
    } else if (const auto hit =
                   pickBox(camera, at[0], at[1], width, height, session.staticBoxes())) {
      const size_t object = session.staticObjects().at(*hit).object;
      VOXLINK_RETURN_IF_ERROR(session.promote(object));
      pending_ = object;
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
