// SPDX-License-Identifier: BSD-3-Clause
#include "scene/detail/surface_fragments.h"

#include <algorithm>
#include <cmath>

#include "format/fragment_extent.h"
#include "format/gradient_codec.h"
#include "geometry/fragment_planes.h"

namespace voxlink::scene {
namespace {

constexpr double kDegrees = 180.0 / 3.14159265358979323846;

// A unit world normal from one in index space: the inverse transpose of the per-axis scaling.
std::array<double, 3> worldNormal(const std::array<double, 3>& n, const double* spacing) {
  const double w[3] = {n[0] / spacing[0], n[1] / spacing[1], n[2] / spacing[2]};
  const double len = std::sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
  return {w[0] / len, w[1] / len, w[2] / len};
}

Status appendPlanes(double mergeAngleDegrees, const geometry::TriangleMesh& mesh,
                    const format::VolumeDescription& d,
                    const geometry::SurfaceVoxelization& surface, SlabVoxels& out) {
  geometry::VoxelGrid indexGrid;
  indexGrid.dims = d.dims;
  VOXLINK_ASSIGN_OR_RETURN(
      geometry::PlaneFragments planes,
      geometry::buildPlaneFragments(mesh, indexGrid, surface, mergeAngleDegrees));
  const double unit = std::min({d.spacing[0], d.spacing[1], d.spacing[2]});
  std::vector<std::array<double, 3>> stored(planes.fragments.size());
  for (size_t v = 0; v < surface.voxels.size(); ++v) {
    out.listLength.push_back(planes.start[v + 1] - planes.start[v]);
    for (uint32_t f = planes.start[v]; f < planes.start[v + 1]; ++f) {
      const geometry::PlaneFragment& p = planes.fragments[f];
      const auto n = worldNormal(p.normal, d.spacing.data());
      const uint16_t code = format::encodeGradient(n[0], n[1], n[2]);
      const auto q = format::decodeGradient(code);
      stored[f] = {q[0], q[1], q[2]};
      // The plane through the fragment's point along the stored normal, in units of `unit`.
      double offset = 0;
      for (int a = 0; a < 3; ++a) offset += q[a] * p.point[a] * d.spacing[a];
      offset /= unit;
      const double steps = std::round(offset / format::kPlaneOffsetUnit);
      if (!(std::abs(steps) <= 32767))
        return makeError(ErrorCode::kUnsupported, "voxel (", surface.voxels[v].x, ", ",
                         surface.voxels[v].y, ", ", surface.voxels[v].z, "): plane offset ", offset,
                         " voxels is beyond the format's 8 (voxels too anisotropic)");
      out.maxOffsetError =
          std::max(out.maxOffsetError, std::abs(offset - steps * format::kPlaneOffsetUnit));
      format::FragmentRecord r{};
      r.word = format::surfaceWord(code, p.material);
      r.offset = int16_t(steps);
      r.extent = format::encodeExtent(p.extentAxis, p.extentLo, p.extentHi, p.convex);
      out.planes.push_back(r);
    }
  }
  // The normal error: each (voxel, triangle) pair against its fragment's stored normal; pairs
  // whose group was left out are counted apart.
  for (size_t v = 0; v < surface.voxels.size(); ++v) {
    const uint32_t begin = surface.triangleStart[v], end = surface.triangleStart[v + 1];
    if (end - begin > 1) out.normalError.countMultiTriangleVoxel();
    for (uint32_t i = begin; i < end; ++i) {
      const uint32_t t = surface.triangleIds[i];
      std::array<double, 3> c[3];
      for (int k = 0; k < 3; ++k)
        for (int a = 0; a < 3; ++a)
          c[k][a] = mesh.positions[3 * size_t(mesh.triangles[3 * size_t(t) + k]) + a];
      const std::array<double, 3> e1{c[1][0] - c[0][0], c[1][1] - c[0][1], c[1][2] - c[0][2]};
      const std::array<double, 3> e2{c[2][0] - c[0][0], c[2][1] - c[0][1], c[2][2] - c[0][2]};
      const std::array<double, 3> n{e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                                    e1[0] * e2[1] - e1[1] * e2[0]};
      if (!(n[0] != 0 || n[1] != 0 || n[2] != 0)) continue;
      if (planes.fragmentOfPair[i] == geometry::kLeftOut) {
        ++out.planePairsLeftOut;
        continue;
      }
      const auto w = worldNormal(n, d.spacing.data());
      const auto& s = stored[planes.fragmentOfPair[i]];
      const double cosine = std::clamp(w[0] * s[0] + w[1] * s[1] + w[2] * s[2], -1.0, 1.0);
      out.normalError.add(std::acos(cosine) * kDegrees);
    }
  }
  return Status::ok();
}

}  // namespace

Status appendFragmentLists(format::SurfaceMode mode, double mergeAngleDegrees,
                           const geometry::TriangleMesh& indexMesh,
                           const format::VolumeDescription& d,
                           const geometry::SurfaceVoxelization& surface, SlabVoxels& out) {
  if (mode == format::SurfaceMode::kPlanes)
    return appendPlanes(mergeAngleDegrees, indexMesh, d, surface, out);
  for (size_t v = 0; v < surface.voxels.size(); ++v) {
    out.listLength.push_back(surface.triangleStart[v + 1] - surface.triangleStart[v]);
    out.triangleRefs.insert(out.triangleRefs.end(),
                            surface.triangleIds.begin() + surface.triangleStart[v],
                            surface.triangleIds.begin() + surface.triangleStart[v + 1]);
  }
  return Status::ok();
}

std::vector<format::TriangleRecord> triangleRecords(const geometry::TriangleMesh& mesh) {
  std::vector<format::TriangleRecord> records(mesh.triangleCount());
  for (size_t t = 0; t < records.size(); ++t) {
    format::TriangleRecord& r = records[t];
    for (int k = 0; k < 3; ++k)
      for (int a = 0; a < 3; ++a)
        r.vertices[3 * k + a] = mesh.positions[3 * size_t(mesh.triangles[3 * t + k]) + a];
    r.material = mesh.triangleMaterials.empty() ? 0u : mesh.triangleMaterials[t];
  }
  return records;
}

}  // namespace voxlink::scene
