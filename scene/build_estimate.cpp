// SPDX-License-Identifier: BSD-3-Clause
#include "scene/detail/build_estimate.h"

#include <algorithm>
#include <cmath>

namespace voxlink::scene {

SceneBuildEstimate estimateSceneBuild(const PlacedScene& placed,
                                      const format::VolumeDescription& grid,
                                      uint64_t volumeVoxels) {
  SceneBuildEstimate e;
  const geometry::TriangleMesh& mesh = placed.mesh;
  auto vertex = [&](uint32_t v, int a) {  // in voxel units
    return (double(mesh.positions[3 * size_t(v) + a]) - grid.origin[a]) / grid.spacing[a];
  };
  // Voxel i spans [i - 0.5, i + 0.5] in index space; the voxelizers clip to the grid, so what
  // lies wholly outside it (a mesh larger than a scene's volume) stores nothing.
  auto outside = [&](const double lo[3], const double hi[3]) {
    for (int a = 0; a < 3; ++a)
      if (hi[a] < -0.5 || lo[a] > double(grid.dims[a]) - 0.5) return true;
    return false;
  };
  for (size_t t = 0; t < mesh.triangleCount(); ++t) {
    double p[3][3];
    for (int c = 0; c < 3; ++c)
      for (int a = 0; a < 3; ++a) p[c][a] = vertex(mesh.triangles[3 * t + c], a);
    double lo[3], hi[3];
    for (int a = 0; a < 3; ++a) {
      lo[a] = std::min({p[0][a], p[1][a], p[2][a]});
      hi[a] = std::max({p[0][a], p[1][a], p[2][a]});
    }
    if (outside(lo, hi)) continue;
    const double u[3] = {p[1][0] - p[0][0], p[1][1] - p[0][1], p[1][2] - p[0][2]};
    const double w[3] = {p[2][0] - p[0][0], p[2][1] - p[0][1], p[2][2] - p[0][2]};
    // Twice the projected areas onto the yz, zx and xy planes.
    const double projected = std::abs(u[1] * w[2] - u[2] * w[1]) +
                             std::abs(u[2] * w[0] - u[0] * w[2]) +
                             std::abs(u[0] * w[1] - u[1] * w[0]);
    if (std::isfinite(projected)) e.surfaceVoxels += 0.5 * projected;
  }
  // A triangle partly outside still counts whole; no more voxels than the grid has, though.
  e.surfaceVoxels = std::min(e.surfaceVoxels, double(grid.dims[0]) * grid.dims[1] * grid.dims[2]);
  for (const geometry::Sphere& s : placed.spheres) {
    const double r = s.radius / grid.spacing[0];
    double lo[3], hi[3];
    for (int a = 0; a < 3; ++a) {
      const double c = (s.center[a] - grid.origin[a]) / grid.spacing[a];
      lo[a] = c - r;
      hi[a] = c + r;
    }
    if (std::isfinite(r) && !outside(lo, hi)) e.sphereRefs += 1.5 * 4.0 * M_PI * r * r;
  }
  e.volumeVoxels = double(volumeVoxels);
  e.peakBytes = e.surfaceVoxels * kSurfaceVoxelBuildBytes + e.sphereRefs * kSphereRefBuildBytes +
                e.volumeVoxels * kVolumeVoxelBuildBytes;
  return e;
}

Status checkSceneBuildFits(const SceneBuildEstimate& estimate, uint64_t memoryBytes,
                           const std::string& scenePath, uint32_t resolution, bool hasVolume) {
  if (estimate.peakBytes <= double(memoryBytes)) return Status();
  const double entries = estimate.surfaceVoxels + estimate.sphereRefs + estimate.volumeVoxels;
  auto gigabytes = [](double bytes) { return std::round(bytes / 1e8) / 10; };
  const std::string where = hasVolume ? std::string(": on the volume's grid")
                                      : ": grid.resolution " + std::to_string(resolution);
  return makeError(
      ErrorCode::kTooLarge, scenePath, where, ": building needs about ",
      std::llround(entries / 1e6), " million voxel entries, ", gigabytes(estimate.peakBytes),
      " GB of memory; this process may use ", gigabytes(double(memoryBytes)), " GB (",
      hasVolume ? "give a smaller volume" : "lower grid.resolution or --resolution", ")");
}

}  // namespace voxlink::scene
