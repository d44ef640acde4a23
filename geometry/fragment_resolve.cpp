// SPDX-License-Identifier: BSD-3-Clause
#include "geometry/fragment_resolve.h"

#include <algorithm>
#include <cmath>

#include "base/parallel_for.h"
#include "geometry/normal_error.h"

namespace voxlink::geometry {
namespace {

struct TriangleInfo {
  std::array<double, 3> normal;  // unit
  double area;                   // in voxel units
};

Result<TriangleInfo> triangleInfo(const TriangleMesh& mesh, const VoxelGrid& grid, uint32_t t) {
  if (size_t(t) >= mesh.triangleCount())
    return makeError(ErrorCode::kInvalidArgument, "fragments: triangle ", t, " out of range");
  std::array<double, 3> c[3];
  for (int k = 0; k < 3; ++k) {
    const float* p = &mesh.positions[3 * size_t(mesh.triangles[3 * size_t(t) + k])];
    c[k] = grid.toGrid(p[0], p[1], p[2]);
  }
  const double e1[3] = {c[1][0] - c[0][0], c[1][1] - c[0][1], c[1][2] - c[0][2]};
  const double e2[3] = {c[2][0] - c[0][0], c[2][1] - c[0][1], c[2][2] - c[0][2]};
  const double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                       e1[0] * e2[1] - e1[1] * e2[0]};
  const double length = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  if (!(length > 0.0))
    return makeError(ErrorCode::kInvalidArgument, "fragments: triangle ", t, " has zero area");
  return TriangleInfo{{n[0] / length, n[1] / length, n[2] / length}, 0.5 * length};
}

}  // namespace

Result<SurfaceVoxelization> resolveVoxelTriangles(const TriangleMesh& mesh, const VoxelGrid& grid,
                                                  std::vector<VoxelTriangle> pairs,
                                                  const SurfaceVoxelizeOptions& options) {
  VOXLINK_RETURN_IF_ERROR(validateGrid(grid));
  base::parallelSort(pairs.begin(), pairs.end(),
                     [](const VoxelTriangle& a, const VoxelTriangle& b) {
                       return a.key != b.key ? a.key < b.key : a.triangle < b.triangle;
                     });
  // Normals and areas of the triangles that occur, computed once each.
  std::vector<int32_t> slot(mesh.triangleCount(), -1);
  std::vector<TriangleInfo> infos;
  for (const VoxelTriangle& p : pairs) {
    if (size_t(p.triangle) >= slot.size())
      return makeError(ErrorCode::kInvalidArgument, "fragments: triangle ", p.triangle,
                       " out of range");
    if (slot[p.triangle] >= 0) continue;
    VOXLINK_ASSIGN_OR_RETURN(TriangleInfo info, triangleInfo(mesh, grid, p.triangle));
    slot[p.triangle] = int32_t(infos.size());
    infos.push_back(info);
  }
  SurfaceVoxelization result;
  NormalErrorTally tally;
  for (size_t begin = 0; begin < pairs.size();) {
    size_t end = begin + 1;
    while (end < pairs.size() && pairs[end].key == pairs[begin].key) ++end;
    const auto xyz = voxelFromKey(pairs[begin].key);
    for (int a = 0; a < 3; ++a)
      if (xyz[a] >= grid.dims[a])
        return makeError(ErrorCode::kInvalidArgument, "fragments: voxel ", xyz[0], ",", xyz[1], ",",
                         xyz[2], " outside the grid");
    // Dominant triangle: largest area, then lowest index (the run is sorted by index).
    uint32_t dominant = pairs[begin].triangle;
    double sum[3] = {0.0, 0.0, 0.0}, weights = 0.0;
    for (size_t i = begin; i < end; ++i) {
      const TriangleInfo& t = infos[size_t(slot[pairs[i].triangle])];
      if (t.area > infos[size_t(slot[dominant])].area) dominant = pairs[i].triangle;
      const double weight = options.normalRule == NormalRule::kAreaWeighted ? t.area : 1.0;
      for (int a = 0; a < 3; ++a) sum[a] += weight * t.normal[a];
      weights += weight;
    }
    const auto& dn = infos[size_t(slot[dominant])].normal;
    std::array<float, 3> normal = {float(dn[0]), float(dn[1]), float(dn[2])};
    const double length = std::sqrt(sum[0] * sum[0] + sum[1] * sum[1] + sum[2] * sum[2]);
    if (options.normalRule != NormalRule::kLargestTriangle && length > 1e-6 * weights)
      normal = {float(sum[0] / length), float(sum[1] / length), float(sum[2] / length)};
    const uint16_t material =
        mesh.triangleMaterials.empty() ? uint16_t(0) : mesh.triangleMaterials[dominant];
    result.voxels.push_back({xyz[0], xyz[1], xyz[2], normal, material});
    if (options.computeNormalError) {
      if (end - begin > 1) tally.countMultiTriangleVoxel();
      for (size_t i = begin; i < end; ++i) {
        const auto& tn = infos[size_t(slot[pairs[i].triangle])].normal;
        const double cosine =
            std::clamp(normal[0] * tn[0] + normal[1] * tn[1] + normal[2] * tn[2], -1.0, 1.0);
        tally.add(std::acos(cosine) * (180.0 / 3.14159265358979323846));
      }
    }
    begin = end;
  }
  if (options.computeNormalError) {
    result.normalError = tally.stats();
    result.normalTally = std::make_shared<NormalErrorTally>(std::move(tally));
  }
  return result;
}

}  // namespace voxlink::geometry
