// SPDX-License-Identifier: BSD-3-Clause
// The moving sphere sets and particles of a dynamic scene (docs/dynamic-scenes.md), re-marked on
// the GPU each update their poses change, nothing read back: a compute pass over the spheres
// (shaders/dynamic_spheres_mark.comp.glsl) appends each sphere to a list per brick of the grid
// (8^3 voxels, viewer/dynamic_scene.cpp says why) that its ball, plus a hundredth of a voxel,
// touches: a head per brick and a node (sphere, next) per reference. The ray tracer
// (shaders/voxlink_dynamic.glsl) walks those bricks and intersects their spheres exactly, as the
// static path intersects a voxel's sphere references (shaders/voxlink_scene.glsl), so a sphere
// at a pose is drawn as the static scene with the sphere there draws it. Lists per brick, not
// per voxel (measured faster): the image does not depend on the granularity, since a ray takes
// the nearest hit inside each brick's chord, brick by brick. Only what moved: the spheres of sets
// that stand can be kept (keep()), and later updates restore them by a copy of the list heads and
// mark only the others on top, as the mesh layer keeps its standing meshes.
#pragma once

#include <epoxy/gl.h>

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "base/error.h"

namespace voxlink::render::gl {

// One sphere as the layer and the static file's SphereRecord store it: world centre and radius.
struct DynamicSphere {
  std::array<float, 3> centre{};
  float radius = 0;
  uint32_t material = 0;  // index into the scene file's materials
};

class GlDynamicSpheres {
 public:
  // Needs a current GL 4.5 context. `dims`: the grid; `origin`/`spacing`: world of voxel 0's
  // centre and the (cubic) voxel edge; bricks of `brickSize` voxels; room for `referenceCapacity`
  // (sphere, brick) references, or what one storage buffer holds.
  static Result<GlDynamicSpheres> create(const std::array<uint32_t, 3>& dims,
                                         const std::array<double, 3>& origin, double spacing,
                                         uint32_t brickSize, uint64_t referenceCapacity);
  // Re-marks the layer with `spheres` (world units): reset(false) and mark(0, spheres).
  Status update(const std::vector<DynamicSphere>& spheres);
  // Empties the lists, or with `onKept` sets them back to the kept part (a copy of the heads the
  // keep() saved and of its counters; the kept nodes stay where they are, as marks after them only
  // append). Queued; reads nothing back.
  void reset(bool onKept);
  // Uploads `spheres` as spheres first.. of the layer (indices stay a sphere's until it is marked
  // again at another) and appends them to the lists on top of what is there. Queued: an upload
  // and a dispatch, nothing read back.
  Status mark(uint32_t first, const std::vector<DynamicSphere>& spheres);
  // Saves the lists as they are as the kept part (GPU copies, nothing read back).
  Status keep();
  void forgetKept();
  bool hasKept() const;
  // Waits and reads two counters: an error when the last update had more references than room.
  Status checkLastUpdate() const;
  // Reads the lists back (tests): per brick index, its spheres sorted.
  std::vector<std::vector<uint32_t>> readLists() const;

  GLuint heads() const;
  GLuint nodes() const;
  GLuint spheres() const;
  uint32_t brickSize() const;
  // Voxel box [lo, hi) of the last update's spheres (rays are clipped to it).
  const std::array<int32_t, 3>& lo() const { return lo_; }
  const std::array<int32_t, 3>& hi() const { return hi_; }
  uint64_t gpuBytes() const;

 private:
  struct State;  // GL objects, owned
  explicit GlDynamicSpheres(std::unique_ptr<State> state);
  std::unique_ptr<State> s_;
  std::array<int32_t, 3> lo_{}, hi_{};
  std::array<int32_t, 3> keptLo_{}, keptHi_{};  // the kept part's box, as lo_/hi_

 public:
  GlDynamicSpheres(GlDynamicSpheres&&) noexcept;
  GlDynamicSpheres& operator=(GlDynamicSpheres&&) noexcept;
  ~GlDynamicSpheres();
};

}  // namespace voxlink::render::gl
