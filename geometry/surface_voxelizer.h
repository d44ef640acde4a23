// SPDX-License-Identifier: BSD-3-Clause
// Exact CPU surface voxelization (the ground-truth path): every voxel whose box a triangle
// overlaps (triangle_box_overlap.h: 13-axis SAT in double precision, with its tie rule), one
// fragment per voxel.
//
//   auto grid = fitGrid(meshBounds(mesh), 1024);
//   auto result = voxelizeSurface(mesh, *grid);
//   for (const SurfaceVoxel& v : result->voxels) ...   // sorted by (z, y, x)
//
// Rules:
//  * Triangles of zero area (exactly collinear or coincident vertices in grid coordinates) are
//    skipped and counted: they have no normal, and in a closed mesh the edges they lie on
//    belong to real triangles that mark the same voxels.
//  * Triangles partly outside the grid mark only the voxels inside it; triangles wholly outside
//    mark none.
//  * The per-voxel fragment keeps one normal and one material (the paper keeps a list):
//    normal   by `normalRule` (default: the area-weighted mean of the unit normals of the
//             triangles overlapping the voxel, normalized; when that sum cancels to
//             < 1e-6 of the summed weights, as on the two sides of a thin sheet, the normal of
//             the dominant triangle);
//    material of the dominant triangle: the largest-area triangle overlapping the voxel
//             (ties: lowest triangle index).
//    What the single normal costs is measured: NormalErrorStats, over all (voxel, overlapping
//    triangle) pairs, the angle between the kept normal and the triangle's normal.
//  * Deterministic: the output does not depend on the number of threads.
// Memory: 16 bytes per (voxel, triangle) overlap plus the output; never a dense dims^3 array.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include "base/error.h"
#include "geometry/triangle_mesh.h"
#include "geometry/voxel_grid.h"

namespace voxlink::geometry {

class NormalErrorTally;

struct SurfaceVoxel {
  uint32_t x, y, z;
  std::array<float, 3> normal;  // unit length, world space (the grid is a uniform scaling)
  uint16_t material;            // index into the mesh's materials
};

enum class NormalRule {
  kAreaWeighted,     // area-weighted mean of the overlapping triangles' unit normals
  kUnweighted,       // plain mean of the overlapping triangles' unit normals
  kLargestTriangle,  // the dominant (largest-area) triangle's normal
};

// Angle in degrees between each kept normal and the normals of the triangles overlapping its
// voxel, over all (voxel, triangle) pairs. p95 has a resolution of 0.01 degrees.
struct NormalErrorStats {
  uint64_t pairs = 0;                // (voxel, triangle) overlaps
  uint64_t multiTriangleVoxels = 0;  // voxels overlapped by more than one triangle
  double meanDegrees = 0.0;
  double p95Degrees = 0.0;
  double maxDegrees = 0.0;
};

inline constexpr uint64_t kDefaultMaxOverlaps = 256ull << 20;  // 4 GiB of overlap records

struct SurfaceVoxelizeOptions {
  NormalRule normalRule = NormalRule::kAreaWeighted;
  bool computeNormalError = true;
  uint64_t maxOverlaps = kDefaultMaxOverlaps;  // more (voxel, triangle) overlaps: kTooLarge
  // Only voxels in these slices (the others are neither tested nor counted in maxOverlaps); a
  // voxel's fragment and error pairs do not depend on the slab, so slabs' results concatenate
  // to the whole grid's.
  ZSlab slab;
  // Also return each voxel's overlapping triangles (SurfaceVoxelization::triangleStart/Ids), for
  // the fragment lists of geometry/fragment_planes.h and the triangle references of a file.
  bool keepTriangleLists = false;
  // Called with the fraction done (0..1), one call at a time, from any thread; may be empty.
  std::function<void(double fraction)> progress;
};

struct SurfaceVoxelization {
  std::vector<SurfaceVoxel> voxels;  // sorted by (z, y, x), one per overlapped voxel
  NormalErrorStats normalError;      // zero unless computeNormalError
  // What normalError was computed from (geometry/normal_error.h), to merge slabs' results.
  std::shared_ptr<const NormalErrorTally> normalTally;
  uint64_t zeroAreaTriangles = 0;  // skipped
  // With keepTriangleLists: voxel v's triangles, ascending, are
  // triangleIds[triangleStart[v] .. triangleStart[v + 1]); empty otherwise.
  std::vector<uint32_t> triangleStart;
  std::vector<uint32_t> triangleIds;
};

// Errors: an invalid grid, a triangle index >= vertexCount, triangleMaterials not one per
// triangle (empty means material 0 everywhere), more overlaps than options.maxOverlaps.
Result<SurfaceVoxelization> voxelizeSurface(const TriangleMesh& mesh, const VoxelGrid& grid,
                                            const SurfaceVoxelizeOptions& options = {});

}  // namespace voxlink::geometry
