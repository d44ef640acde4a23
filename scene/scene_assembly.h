// SPDX-License-Identifier: BSD-3-Clause
// Turns a scene description into one VoxLink buffer: loads every mesh, particle file and volume
// it names, places them with their transforms, voxelizes the geometry exactly on the CPU
// (geometry/surface_voxelizer.h, geometry/sphere_voxelizer.h) and merges everything into the
// bricks and rows of a version 2 file (format/scene_builder.h).
//
// The grid: with a volume object it is the volume's own grid (dims, spacing, origin), so the
// volume's voxels are kept exactly as `voxlink convert` wrote them and geometry is placed in
// the volume's world coordinates; without one it is fitted around every object's bounds with
// `grid.resolution` voxels along the longest axis (geometry/voxel_grid.h, fitGrid).
#pragma once

#include <cstdint>
#include <functional>
#include <string>

#include "base/error.h"
#include "base/rank_group.h"
#include "format/bricked_volume.h"
#include "format/file_writer.h"
#include "geometry/surface_voxelizer.h"
#include "scene/scene_description.h"

namespace voxlink::scene {

struct SceneBuildReport {
  uint64_t triangles = 0, spheres = 0, materials = 0;
  uint64_t surfaceVoxels = 0, sphereVoxels = 0, sphereRefs = 0, volumeVoxels = 0;
  uint64_t zeroAreaTriangles = 0;
  geometry::NormalErrorStats normalError;  // what the kept fragments' normals cost
  format::SurfaceMode surfaceMode = format::SurfaceMode::kMean;
  uint64_t fragments = 0;          // FRAG or TRID entries (surface modes planes, triangles)
  double maxPlaneOffsetError = 0;  // planes: largest offset rounding, in voxels
  uint64_t planePairsLeftOut = 0;  // planes: (voxel, triangle) pairs not in normalError
  std::array<uint32_t, 3> dims{0, 0, 0};
  std::array<double, 3> spacing{1, 1, 1};
  double loadSeconds = 0, voxelizeSeconds = 0, mergeSeconds = 0;
};

struct SceneBuildOutput {
  format::BrickedVolume volume;  // write with format::writeBrickedVolume
  SceneBuildReport report;
};

// `progress(stage, fraction)` is called between stages ("load", "voxelize", "merge").
using SceneProgress = std::function<void(const char* stage, double fraction)>;

// Voxelizes the scene's meshes (one mesh, in index space: unit voxels, centres on integers).
// The default is the exact CPU path (geometry::voxelizeSurface); the CLI passes the GL path
// (render/gl/gl_voxelizer.h) for `--voxelizer gl`, which keeps scene/ free of GL.
// `progress(fraction)` reports the voxelizer's own progress (may be ignored).
using SurfaceVoxelizer = std::function<Result<geometry::SurfaceVoxelization>(
    const geometry::TriangleMesh& mesh, const geometry::VoxelGrid& grid,
    const std::function<void(double fraction)>& progress)>;

// On several MPI ranks (`ranks`; null: this process alone) every rank must call it; each
// voxelizes its slab of brick layers (scene/detail/scene_ranks.h) and rank 0 alone gets the merged
// volume and the whole report (the others an empty volume). Errors are agreed: every rank gets
// the lowest failing rank's. A SurfaceVoxelizer other than the exact one needs one process.
Result<SceneBuildOutput> buildScene(const SceneDescription& scene,
                                    const SceneProgress& progress = {},
                                    const SurfaceVoxelizer& surfaceVoxelizer = {},
                                    base::RankGroup* ranks = nullptr);

}  // namespace voxlink::scene
