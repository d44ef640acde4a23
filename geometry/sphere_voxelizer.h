// SPDX-License-Identifier: BSD-3-Clause
// Voxelization of implicit spheres (particles): for every sphere exactly the voxels whose box it
// overlaps, i.e. the squared distance from the centre to the voxel's closed box is <= r^2
// (evaluated in grid coordinates in double precision; touching counts). Solid: a sphere marks
// its interior voxels too. Spheres partly outside the grid mark only the voxels inside it.
//
// The result lists, per overlapped voxel, the indices of the spheres overlapping it, CSR-like:
//   voxel n = voxels[n], its spheres = sphereIds[offsets[n] .. offsets[n + 1]) (ascending).
// Voxels are sorted by (z, y, x). Memory: 12 bytes per (voxel, sphere) overlap plus the output.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "base/error.h"
#include "geometry/particle_loader.h"
#include "geometry/voxel_grid.h"

namespace voxlink::geometry {

struct SphereVoxelization {
  std::vector<std::array<uint32_t, 3>> voxels;  // x, y, z
  std::vector<uint64_t> offsets;                // voxels.size() + 1 entries
  std::vector<uint32_t> sphereIds;
};

inline constexpr uint64_t kDefaultMaxSphereOverlaps = 256ull << 20;

// Which voxels a sphere marks: every voxel its ball overlaps, or only those its surface passes
// through. A ray tracer that intersects the exact sphere needs only the shell: the point where
// a ray meets the sphere lies on the surface, so in a shell voxel (a 25-voxel-radius sphere:
// 7.5k shell voxels instead of 72k).
enum class SphereFill { kSolid, kShell };

// Errors: an invalid grid, a non-finite centre or a radius that is not finite and > 0 (names the
// sphere), more overlaps than maxOverlaps (kTooLarge). Only voxels in `slab` are marked (and
// counted against maxOverlaps); slabs' results concatenate to the whole grid's.
Result<SphereVoxelization> voxelizeSpheres(const std::vector<Sphere>& spheres,
                                           const VoxelGrid& grid,
                                           uint64_t maxOverlaps = kDefaultMaxSphereOverlaps,
                                           SphereFill fill = SphereFill::kSolid, ZSlab slab = {});

// Exact test used by voxelizeSpheres: sphere (centre and radius in grid coordinates) against
// voxel (i, j, k)'s box [i, i+1] x [j, j+1] x [k, k+1].
inline bool sphereOverlapsVoxel(const std::array<double, 3>& centre, double radius, int64_t i,
                                int64_t j, int64_t k) {
  const int64_t lo[3] = {i, j, k};
  double d2 = 0.0;
  for (int a = 0; a < 3; ++a) {
    const double below = double(lo[a]) - centre[a], above = centre[a] - double(lo[a] + 1);
    const double d = below > 0.0 ? below : (above > 0.0 ? above : 0.0);
    d2 += d * d;
  }
  return d2 <= radius * radius;
}

// The sphere's surface meets the voxel's closed box: the nearest point of the box is within the
// radius and the farthest corner is not inside it (touching counts).
inline bool sphereSurfaceInVoxel(const std::array<double, 3>& centre, double radius, int64_t i,
                                 int64_t j, int64_t k) {
  if (!sphereOverlapsVoxel(centre, radius, i, j, k)) return false;
  const int64_t lo[3] = {i, j, k};
  double far2 = 0.0;
  for (int a = 0; a < 3; ++a) {
    const double d =
        std::max(std::abs(double(lo[a]) - centre[a]), std::abs(double(lo[a] + 1) - centre[a]));
    far2 += d * d;
  }
  return far2 >= radius * radius;
}

}  // namespace voxlink::geometry
