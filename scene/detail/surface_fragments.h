// SPDX-License-Identifier: BSD-3-Clause
// The fragment lists of `scene build --surface planes|triangles` (format/layout.h, version 2.1):
// from a voxelization that kept its triangle lists, each surface voxel's planes (merged by
// normal, geometry/fragment_planes.h) quantized as the file stores them, or its triangle
// references. scene_assembly.cpp calls it per slab, so MPI ranks each make their slab's lists.
#pragma once

#include <vector>

#include "base/error.h"
#include "format/bricked_volume.h"
#include "geometry/surface_voxelizer.h"
#include "geometry/triangle_mesh.h"
#include "scene/detail/scene_ranks.h"

namespace voxlink::scene {

// `indexMesh` is the mesh in index space (unit voxels, centres on integers), as voxelized;
// `surface` its voxelization with keepTriangleLists. Appends one list per surface voxel to
// `out` (listLength, planes or triangleRefs) and, for planes, tallies in out.normalError the
// angle between each triangle's world normal and its fragment's stored (quantized) normal.
// Errors: a plane offset the format cannot hold (voxels more than 8x longer along one axis).
Status appendFragmentLists(format::SurfaceMode mode, double mergeAngleDegrees,
                           const geometry::TriangleMesh& indexMesh,
                           const format::VolumeDescription& d,
                           const geometry::SurfaceVoxelization& surface, SlabVoxels& out);

// TRIS: every triangle of the world-space mesh, with its material.
std::vector<format::TriangleRecord> triangleRecords(const geometry::TriangleMesh& worldMesh);

}  // namespace voxlink::scene
