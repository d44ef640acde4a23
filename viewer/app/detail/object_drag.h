// SPDX-License-Identifier: BSD-3-Clause
// The math of dragging a scene object with the mouse, free of GL and GLFW so tests can check it:
// a cursor motion in pixels becomes a world translation in the camera's view plane at the
// object's depth (the point under the cursor stays under it), and a translated box is clamped
// into the grid, per axis, saying which axes were clamped.
#pragma once

#include <array>

#include "base/error.h"
#include "render/camera.h"
#include "scene/scene_animation.h"

namespace voxlink::viewer {

using render::Box;
using render::Camera;

// World translation, parallel to the image plane, that keeps `depthPoint` under the cursor when
// the cursor moves by (dx, dy) pixels (y down) in a viewport `viewportHeight` pixels high.
// Errors: a point at or behind the eye, a height < 1, a non-finite input.
Result<glm::dvec3> viewPlaneTranslation(const Camera& camera, const glm::dvec3& depthPoint,
                                        double dxPixels, double dyPixels, double viewportHeight);

struct ClampedTranslation {
  glm::dvec3 translation{0.0};
  std::array<bool, 3> clamped{};  // per axis: `wanted` would have left the limits
};

// The translation nearest `wanted` (per axis) that keeps `box` translated by it inside
// `limits`. Errors: a box wider than the limits on an axis (no translation fits).
Result<ClampedTranslation> clampTranslation(const Box& box, const glm::dvec3& wanted,
                                            const Box& limits);

struct DraggedPose {
  scene::Pose pose;
  std::array<bool, 3> clamped{};  // per axis: the grid stopped the drag
};

// The pose of an object dragged by (dx, dy) pixels since the drag began: `start` translated in
// the view plane at the depth of `startBox`'s centre (its world box at `start`), the translation
// clamped so that the box stays inside `grid`. Errors: those of the two functions above.
Result<DraggedPose> dragPose(const Camera& camera, const scene::Pose& start, const Box& startBox,
                             const Box& grid, double dxPixels, double dyPixels,
                             double viewportHeight);

}  // namespace voxlink::viewer
