// SPDX-License-Identifier: BSD-3-Clause
// The paper's per-voxel fragment lists as planes: the triangles overlapping a voxel are grouped
// so that only triangles of one material whose normals agree within `mergeAngleDegrees` share a
// fragment; the two sides of a thin part, a crease sharper than the angle and a material border
// each keep their own. A fragment is the plane through the area-weighted centroid of its
// triangles' parts inside the voxel, with their area-weighted mean normal.
//
//   SurfaceVoxelizeOptions o;  o.keepTriangleLists = true;
//   auto surface = voxelizeSurface(mesh, grid, o);
//   auto planes = buildPlaneFragments(mesh, grid, *surface, 20.0);
//
// Grouping is greedy and deterministic: the voxel's triangles by decreasing area inside the
// voxel (ties: lower index first), each joining the first group of its material whose first
// (largest) triangle's normal is within the angle, or starting a new group. A group whose
// triangles cover less than kMinFragmentArea of the voxel is left out unless it is the voxel's
// largest: its plane would cross the whole voxel in front of the surface that is really there
// (docs/geometry.md measures it), and the voxels those triangles mostly lie in keep them.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "base/error.h"
#include "geometry/surface_voxelizer.h"
#include "geometry/triangle_mesh.h"
#include "geometry/voxel_grid.h"

namespace voxlink::geometry {

// `scene build --fragment-angle`'s default (docs/geometry.md, "Fragment lists", measures it).
inline constexpr double kDefaultMergeAngleDegrees = 5.0;
// Smallest area (in voxel faces) of a group's triangles inside the voxel that gets a fragment.
inline constexpr double kMinFragmentArea = 0.05;
// fragmentOfPair of a triangle whose group was left out.
inline constexpr uint32_t kLeftOut = UINT32_MAX;

struct PlaneFragment {
  std::array<double, 3> normal;  // unit, grid coordinates (the mesh's space / grid.spacing)
  std::array<double, 3> point;   // on the plane, grid coordinates relative to the voxel centre
  uint16_t material;
  // Where the triangles' parts lie in the voxel, seen along axis `extentAxis` (the normal's
  // largest component): bounds of axes (extentAxis + 1) % 3 and (extentAxis + 2) % 3 in
  // voxel-local [0, 1] (format/fragment_extent.h stores them).
  int extentAxis = 0;
  std::array<double, 2> extentLo{0, 0}, extentHi{1, 1};
  // Every other plane of the voxel lies behind this one's piece and this one behind theirs (by
  // their points): a convex crease, where the surface is the planes' intersection.
  bool convex = false;
};

struct PlaneFragments {
  // Voxel v of the voxelization has fragments[start[v] .. start[v + 1]).
  std::vector<uint32_t> start;
  std::vector<PlaneFragment> fragments;
  // For each entry of the voxelization's triangleIds, the fragment (index into fragments) its
  // triangle joined, or kLeftOut: what the normal error is measured over.
  std::vector<uint32_t> fragmentOfPair;
};

// `surface` must come from voxelizeSurface(mesh, grid, {keepTriangleLists = true}). Errors: no
// triangle lists, an angle outside [0, 180].
Result<PlaneFragments> buildPlaneFragments(const TriangleMesh& mesh, const VoxelGrid& grid,
                                           const SurfaceVoxelization& surface,
                                           double mergeAngleDegrees);

}  // namespace voxlink::geometry
