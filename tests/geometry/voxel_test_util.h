// SPDX-License-Identifier: BSD-3-Clause
// Brute-force references for the voxelizer tests: every voxel of the grid against every
// triangle or sphere, with the plain 13-axis SAT and the plain distance test.
#pragma once

#include <array>
#include <map>
#include <vector>

#include "geometry/detail/triangle_box_overlap.h"
#include "geometry/sphere_voxelizer.h"
#include "geometry/triangle_mesh.h"
#include "geometry/voxel_grid.h"

namespace voxlink::geometry::testing {

inline Vec3d cornerInGrid(const TriangleMesh& mesh, const VoxelGrid& grid, size_t t, int c) {
  const float* p = &mesh.positions[3 * size_t(mesh.triangles[3 * t + c])];
  return grid.toGrid(p[0], p[1], p[2]);
}

inline bool zeroArea(const Vec3d& a, const Vec3d& b, const Vec3d& c) {
  const Vec3d e = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  const Vec3d f = {c[0] - b[0], c[1] - b[1], c[2] - b[2]};
  return e[1] * f[2] - e[2] * f[1] == 0.0 && e[2] * f[0] - e[0] * f[2] == 0.0 &&
         e[0] * f[1] - e[1] * f[0] == 0.0;
}

// voxel key -> overlapping triangles (ascending), zero-area triangles skipped.
inline std::map<uint64_t, std::vector<uint32_t>> bruteForceSurface(const TriangleMesh& mesh,
                                                                   const VoxelGrid& grid) {
  std::map<uint64_t, std::vector<uint32_t>> out;
  for (size_t t = 0; t < mesh.triangleCount(); ++t) {
    const Vec3d a = cornerInGrid(mesh, grid, t, 0), b = cornerInGrid(mesh, grid, t, 1),
                c = cornerInGrid(mesh, grid, t, 2);
    if (zeroArea(a, b, c)) continue;
    for (uint32_t k = 0; k < grid.dims[2]; ++k)
      for (uint32_t j = 0; j < grid.dims[1]; ++j)
        for (uint32_t i = 0; i < grid.dims[0]; ++i)
          if (triangleOverlapsVoxelSat(a, b, c, i, j, k))
            out[voxelKey(i, j, k)].push_back(uint32_t(t));
  }
  return out;
}

inline std::map<uint64_t, std::vector<uint32_t>> bruteForceSpheres(
    const std::vector<Sphere>& spheres, const VoxelGrid& grid) {
  std::map<uint64_t, std::vector<uint32_t>> out;
  for (size_t s = 0; s < spheres.size(); ++s) {
    const auto c = grid.toGrid(spheres[s].center[0], spheres[s].center[1], spheres[s].center[2]);
    for (uint32_t k = 0; k < grid.dims[2]; ++k)
      for (uint32_t j = 0; j < grid.dims[1]; ++j)
        for (uint32_t i = 0; i < grid.dims[0]; ++i)
          if (sphereOverlapsVoxel(c, spheres[s].radius / grid.spacing, i, j, k))
            out[voxelKey(i, j, k)].push_back(uint32_t(s));
  }
  return out;
}

}  // namespace voxlink::geometry::testing
