// SPDX-License-Identifier: BSD-3-Clause
#include "viewer/app/detail/object_drag.h"

#include <algorithm>
#include <cmath>

namespace voxlink::viewer {

Result<glm::dvec3> viewPlaneTranslation(const Camera& camera, const glm::dvec3& depthPoint,
                                        double dxPixels, double dyPixels, double viewportHeight) {
  if (!std::isfinite(dxPixels) || !std::isfinite(dyPixels) || !std::isfinite(viewportHeight) ||
      viewportHeight < 1)
    return makeError(ErrorCode::kInvalidArgument,
                     cat("drag: cursor motion ", dxPixels, ",", dyPixels, " in a viewport ",
                         viewportHeight, " pixels high"));
  const double depth = glm::dot(depthPoint - camera.eye(), -camera.back());
  if (!(depth > 0))
    return makeError(ErrorCode::kInvalidArgument,
                     cat("drag: the object is not in front of the camera (depth ", depth, ")"));
  // A pixel's side in world units at that depth (the image plane at distance 1 is
  // 2 tan(fov/2) high).
  const double pixel = 2 * depth * std::tan(0.5 * camera.fovYDeg() * M_PI / 180) / viewportHeight;
  return camera.right() * (dxPixels * pixel) - camera.up() * (dyPixels * pixel);
}

Result<ClampedTranslation> clampTranslation(const Box& box, const glm::dvec3& wanted,
                                            const Box& limits) {
  ClampedTranslation r;
  for (int a = 0; a < 3; ++a) {
    const double lo = limits.lo[a] - box.lo[a], hi = limits.hi[a] - box.hi[a];
    if (lo > hi)
      return makeError(ErrorCode::kInvalidArgument,
                       cat("drag: the object (", "xyz"[a], " ", box.lo[a], "..", box.hi[a],
                           ") is wider than the grid (", limits.lo[a], "..", limits.hi[a], ")"));
    r.translation[a] = std::clamp(wanted[a], lo, hi);
    r.clamped[size_t(a)] = r.translation[a] != wanted[a];
  }
  return r;
}

Result<DraggedPose> dragPose(const Camera& camera, const scene::Pose& start, const Box& startBox,
                             const Box& grid, double dxPixels, double dyPixels,
                             double viewportHeight) {
  VOXLINK_ASSIGN_OR_RETURN(
      glm::dvec3 wanted,
      viewPlaneTranslation(camera, startBox.center(), dxPixels, dyPixels, viewportHeight));
  VOXLINK_ASSIGN_OR_RETURN(ClampedTranslation clamped, clampTranslation(startBox, wanted, grid));
  DraggedPose r;
  r.pose = start;
  for (int a = 0; a < 3; ++a) r.pose.translate[size_t(a)] += clamped.translation[a];
  r.clamped = clamped.clamped;
  return r;
}

}  // namespace voxlink::viewer
