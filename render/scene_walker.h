// SPDX-License-Identifier: BSD-3-Clause
// What a ray meets in a scene, front to back: the one question the ray-traced scene mode asks of
// its geometry. Two answers exist: VoxelSceneWalker walks the VoxLink file (voxelized surfaces,
// exact spheres in their voxels, volume samples), and an exact tracer answers from the original
// meshes and spheres. EffectsTracer (effects_tracer.h) shades and spawns rays on top of either,
// so the difference of their images is what voxelization costs and nothing else.
#pragma once

#include <functional>
#include <glm/glm.hpp>
#include <span>

#include "format/layout.h"
#include "render/camera.h"

namespace voxlink::render {

struct SceneEvent {
  enum class Kind { kSurface, kVolume };
  Kind kind = Kind::kSurface;
  // kSurface: the hit's distance along the ray; kVolume: the chord [t, tEnd) of one voxel.
  double t = 0;
  double tEnd = 0;
  // kSurface: unit world normal as stored (outward for closed meshes and spheres; not turned
  // towards the ray) and the index into materials().
  glm::dvec3 normal{0.0};
  uint32_t material = 0;
  // kVolume: the stored value in source units and the unit direction of its gradient (or zero).
  double value = 0;
  glm::dvec3 gradient{0.0};
};

class SceneWalker {
 public:
  virtual ~SceneWalker() = default;
  // Calls visit for every event of origin + t * direction (unit direction) with t in
  // [tMin, tMax], front to back, until visit returns false.
  virtual void walk(const Ray& ray, double tMin, double tMax,
                    const std::function<bool(const SceneEvent&)>& visit) const = 0;
  virtual std::span<const format::MaterialRecord> materials() const = 0;
  // World box that holds everything; rays that leave it meet nothing more.
  virtual Box bounds() const = 0;
  // How far (world units) a secondary ray starts off a surface along its normal, and how far a
  // shadow ray starts along its own direction: a voxelized surface is one to two voxels thick and
  // would otherwise stop the ray it spawned; an exact surface needs only a rounding margin.
  virtual double surfaceOffset() const = 0;
  virtual double shadowStartOffset() const = 0;
  // The smallest voxel spacing: the unit of volume opacity (correctedAlpha). Exact scenes without
  // a volume return any positive length.
  virtual double opacityUnit() const = 0;
};

}  // namespace voxlink::render
