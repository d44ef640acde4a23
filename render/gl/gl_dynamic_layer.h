// SPDX-License-Identifier: BSD-3-Clause
// The dynamic layer of a dynamic scene (docs/dynamic-scenes.md): the moving meshes re-voxelized
// every frame by the GL voxelizer's raster stage (shaders/gl_voxelize.*.glsl, conservative
// coverage), whose fragments add their triangle straight into a GPU-side structure
// (shaders/dynamic_layer.glsl), with nothing stored per fragment and nothing read back:
//   - a brick map over the whole grid: per brick a pool slot, or empty;
//   - a pool of bricks (sized from the moving objects' bounds, split over up to kMaxPoolBuffers
//     storage buffers where one binding's GL_MAX_SHADER_STORAGE_BLOCK_SIZE does not hold it,
//     slot s in buffer s / slotsPerPoolBuffer()): per voxel the sum of its
//     triangles' area x unit normal in fixed point (atomic adds) and material + 1; a brick gets
//     its slot from a hash table over the slots, and only the slots an update used are zeroed
//     by the next (shaders/dynamic_layer_build.comp.glsl).
// A layer can keep its state (keep()): a later update on top of it re-voxelizes only the meshes
// that moved and restores the others' bricks by a copy (shaders/dynamic_layer_keep.comp.glsl);
// sums of integers do not depend on order, so the layer equals a full update's.
// The ray tracer (DynamicSceneRenderer) reads both beside the static file. The rule is the host's
// mean rule (area-weighted normal) in fixed point, without the host's depth sort (a sum does not
// need it) and, per voxel, the highest material index of its triangles (the host: the largest
// triangle's).
#pragma once

#include <epoxy/gl.h>

#include <array>
#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

#include "base/error.h"
#include "render/gl/shader_program.h"

namespace voxlink::render::gl {

// Bricks a box of `extent` voxels can touch anywhere in the grid.
uint64_t dynamicBrickBound(const std::array<double, 3>& extent, uint32_t brickSize,
                           const std::array<uint32_t, 3>& dims);

class GlDynamicLayer {
 public:
  static constexpr uint32_t kMaxPoolBuffers = 4;
  // Needs a current GL 4.5 context. The pool holds `brickCapacity` bricks, or as many as
  // kMaxPoolBuffers storage buffers of GL_MAX_SHADER_STORAGE_BLOCK_SIZE (or of `bytesPerBuffer`
  // where that is smaller and not 0: tests split a small pool) do. Errors: a grid wider than the
  // largest framebuffer, a brick larger than one buffer.
  static Result<GlDynamicLayer> create(const std::array<uint32_t, 3>& dims, uint32_t brickSize,
                                       uint64_t brickCapacity, uint64_t bytesPerBuffer = 0);

  // Re-voxelizes the triangles (vertices in grid coordinates: voxel i spans [i, i + 1)) into the
  // layer, each with its material (a voxel keeps the highest of its triangles'). Queues uploads,
  // draws and dispatches; reads nothing back.
  // With `onKept` the layer starts from what keep() saved instead of empty (the voxel box too).
  Status update(const std::vector<float>& gridPositions, const std::vector<uint32_t>& triangles,
                const std::vector<uint32_t>& triangleMaterials, bool onKept = false);
  // Saves the layer as the last update left it, for updates `onKept`. Waits for the GPU and reads
  // the used-slot count once (not per frame). Errors: the last update dropped bricks.
  Status keep();
  void forgetKept();
  bool hasKept() const;
  // Waits and reads two counters: an error when the last update had more bricks than the pool
  // holds (its layer would miss voxels).
  Status checkLastUpdate() const;
  // Reads the layer back (tests, diagnostics): per occupied voxel its key
  // (geometry::voxelKey) and (normal sum x, y, z, material + 1), sorted by key.
  std::vector<std::pair<uint64_t, std::array<int32_t, 4>>> readVoxels() const;

  GLuint brickMap() const;
  // The pool's storage buffers (slot s in buffer s / slotsPerPoolBuffer()) and the defines the
  // shaders read them with (VXL_DYN_POOLS, VXL_DYN_POOL_SLOTS).
  uint32_t poolBuffers() const;
  GLuint poolBuffer(uint32_t i) const;
  uint64_t slotsPerPoolBuffer() const;
  std::vector<ShaderDefine> poolDefines() const;
  uint32_t brickSize() const;
  // Voxel box [lo, hi) holding the last update's triangles (rays are clipped to it).
  const std::array<int32_t, 3>& lo() const { return lo_; }
  const std::array<int32_t, 3>& hi() const { return hi_; }
  uint64_t gpuBytes() const;

 private:
  struct State;  // GL objects, owned
  explicit GlDynamicLayer(std::unique_ptr<State> state);
  void copyKeptBricks(int pass);  // 0: pool -> kept, 1: kept -> pool
  void copyKeptTables(bool toKept);
  void restoreKept();
  std::unique_ptr<State> s_;
  std::array<int32_t, 3> lo_{}, hi_{}, keptLo_{}, keptHi_{};

 public:
  GlDynamicLayer(GlDynamicLayer&&) noexcept;
  GlDynamicLayer& operator=(GlDynamicLayer&&) noexcept;
  ~GlDynamicLayer();
};

}  // namespace voxlink::render::gl
