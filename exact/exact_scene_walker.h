// SPDX-License-Identifier: BSD-3-Clause
// SceneWalker answered from a scene's original geometry: the triangles and spheres that
// `voxlink scene build` voxelizes (scene/scene_geometry.h), with the same material table, traced
// with Embree 3. Embree finds candidates in float; every reported distance and normal is
// recomputed in double from the stored vertices and spheres, so the events are exact up to
// rounding. Normals are what the surface voxelizer averages per voxel: face normals (vertex
// normals of a file are ignored by both), so the only difference from VoxelSceneWalker is
// voxelization. Every surface along the ray is reported (semi-transparent ones are composited):
// rtcIntersect1 is called again from each hit, with the hits already reported filtered out.
#pragma once

#include <embree3/rtcore.h>

#include <cstdint>
#include <memory>
#include <vector>

#include "base/error.h"
#include "render/scene_walker.h"
#include "scene/scene_description.h"
#include "scene/scene_geometry.h"

namespace voxlink::exact {

class ExactSceneWalker : public render::SceneWalker {
 public:
  // Loads and places the scene's meshes and spheres. bounds(): the grid box `scene build` fits
  // at `resolution` voxels along the longest axis (0: the scene's grid.resolution), so rays
  // enter and leave as they do in the voxel file. A scene with a volume object is refused.
  static Result<std::unique_ptr<ExactSceneWalker>> open(const scene::SceneDescription& scene,
                                                        uint32_t resolution = 0);
  // Placed geometry and the world box to clip rays to (tests build scenes by hand).
  static Result<std::unique_ptr<ExactSceneWalker>> create(scene::PlacedScene placed,
                                                          const render::Box& bounds);
  ~ExactSceneWalker() override;
  ExactSceneWalker(const ExactSceneWalker&) = delete;
  ExactSceneWalker& operator=(const ExactSceneWalker&) = delete;

  void walk(const render::Ray& ray, double tMin, double tMax,
            const std::function<bool(const render::SceneEvent&)>& visit) const override;
  std::span<const format::MaterialRecord> materials() const override { return placed_.materials; }
  render::Box bounds() const override { return box_; }
  // Rounding margins only: hits are double precision on float vertices.
  double surfaceOffset() const override { return epsilon_; }
  double shadowStartOffset() const override { return epsilon_; }
  double opacityUnit() const override { return 2.0 * box_.radius(); }

  size_t triangleCount() const { return placed_.mesh.triangleCount(); }
  size_t sphereCount() const { return placed_.spheres.size(); }

 private:
  struct WalkContext;
  ExactSceneWalker() = default;
  Status build();
  static void sphereBounds(const RTCBoundsFunctionArguments* args);
  static void sphereIntersect(const RTCIntersectFunctionNArguments* args);
  static void skipReported(const RTCFilterFunctionNArguments* args);
  render::SceneEvent triangleEvent(uint32_t triangle, const glm::dvec3& o,
                                   const glm::dvec3& d) const;

  scene::PlacedScene placed_;
  std::vector<glm::dvec3> faceNormals_;  // unit, one per triangle (zero for degenerate ones)
  render::Box box_{};
  double epsilon_ = 0;  // world units: 1e-6 of the box diagonal
  RTCDevice device_ = nullptr;
  RTCScene scene_ = nullptr;
  unsigned meshGeometry_ = RTC_INVALID_GEOMETRY_ID;
  unsigned sphereGeometry_ = RTC_INVALID_GEOMETRY_ID;
};

}  // namespace voxlink::exact
