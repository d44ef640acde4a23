// SPDX-License-Identifier: BSD-3-Clause
// `voxlink scene build` on several MPI ranks (docs/scale.md, "Scene builds"): every rank loads
// the scene's meshes and particle files itself, voxelizes only the triangles and spheres that
// reach its slab of brick layers, and sends its voxels to rank 0, which merges them with the
// volume into the one file. A voxel's fragment depends only on the triangles and spheres
// overlapping it, all of which its slab's rank sees, so the file is the one process's.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "base/error.h"
#include "base/rank_group.h"
#include "format/file_writer.h"
#include "geometry/normal_error.h"
#include "geometry/voxel_grid.h"
#include "scene/scene_geometry.h"

namespace voxlink::scene {

// The slices rank `rank` of `ranks` voxelizes: brick layers [L*rank/ranks, L*(rank+1)/ranks) of
// the L = ceil(depth / brick) layers along z, so the split depends only on the rank count.
geometry::ZSlab rankSlab(uint32_t depth, uint32_t brick, int rank, int ranks);

struct SurfaceEntry {  // what SceneBuilder::addSurface takes
  uint32_t x, y, z;
  uint16_t normalCode, material;
};
struct SphereEntry {  // what SceneBuilder::addSphereRef takes
  uint32_t x, y, z, sphere;
};
static_assert(sizeof(SurfaceEntry) == 16 && sizeof(SphereEntry) == 16);

// What one rank's slab holds, or, after gatherSlabVoxels, every slab's on rank 0.
struct SlabVoxels {
  std::vector<SurfaceEntry> surface;
  // Fragment lists (surface modes planes and triangles), one per surface entry in its order:
  // entry i's list is listLength[i] records of planes or triangleRefs, after the previous ones.
  std::vector<uint32_t> listLength;
  std::vector<format::FragmentRecord> planes;
  std::vector<uint32_t> triangleRefs;
  double maxOffsetError = 0;       // largest plane offset rounding, in voxels
  uint64_t planePairsLeftOut = 0;  // (voxel, triangle) pairs of groups given no plane
  std::vector<SphereEntry> sphereRefs;
  uint64_t sphereVoxels = 0;
  geometry::NormalErrorTally normalError;
};

// Collective: every rank's voxels and lists on rank 0 (in rank order) with their tallies merged;
// the other ranks get an empty set. One process gets its own back.
SlabVoxels gatherSlabVoxels(base::RankGroup& ranks, SlabVoxels mine);

// Collective: ok when every rank placed the same triangles, spheres and materials as rank 0
// (counts and a CRC-32C of them); otherwise, on every rank, an error naming the lowest rank
// that differs (a node that sees another copy of an input file).
Status checkSameGeometry(base::RankGroup& ranks, const PlacedScene& placed,
                         const std::string& scenePath);

// Collective: rank 0's description on every rank.
void broadcastDescription(base::RankGroup& ranks, format::VolumeDescription& description);

}  // namespace voxlink::scene
