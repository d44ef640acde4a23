// SPDX-License-Identifier: BSD-3-Clause
#include "format/detail/fragment_validator.h"

#include <cmath>

#include "format/fragment_extent.h"
#include "format/gradient_codec.h"

namespace voxlink::format {
namespace {

Status checkPlanes(const VoxLinkFile& f) {
  const FileHeader& h = f.header();
  const auto fragments = f.fragments();
  for (uint64_t i = 0; i < h.fragmentCount; ++i) {
    const FragmentRecord& r = fragments[i];
    if (surfaceMaterial(r.word) >= h.materialCount)
      return makeError(ErrorCode::kCorrupt, f.path(), ": section FRAG: fragment ", i,
                       " names material ", surfaceMaterial(r.word), " of ", h.materialCount);
    if (surfaceNormal(r.word) == kZeroGradient || !isCanonicalGradientCode(surfaceNormal(r.word)))
      return makeError(ErrorCode::kCorrupt, f.path(), ": section FRAG: fragment ", i,
                       " has the reserved or non-canonical normal code 0x", std::hex,
                       surfaceNormal(r.word));
    if (h.versionMinor < kVersionMinorExtents && r.extent != 0)
      return makeError(ErrorCode::kCorrupt, f.path(), ": section FRAG: fragment ", i,
                       ".extent is not zero in a version 2.", h.versionMinor, " file");
    if (!isValidExtent(r.extent))
      return makeError(ErrorCode::kCorrupt, f.path(), ": section FRAG: fragment ", i, ".extent 0x",
                       std::hex, r.extent,
                       " is not a box (axis 3, bit 15 set, or an interval under 1/8 voxel)");
  }
  return Status::ok();
}

Status checkTriangles(const VoxLinkFile& f, std::span<const uint32_t> starts) {
  const FileHeader& h = f.header();
  const auto triangles = f.triangles();
  for (uint32_t t = 0; t < h.triangleCount; ++t) {
    const TriangleRecord& r = triangles[t];
    for (float v : r.vertices)
      if (!std::isfinite(v))
        return makeError(ErrorCode::kCorrupt, f.path(), ": section TRIS: triangle ", t,
                         " has a vertex that is not finite");
    if (r.material >= h.materialCount)
      return makeError(ErrorCode::kCorrupt, f.path(), ": section TRIS: triangle ", t, ".material ",
                       r.material, " is not in the table of ", h.materialCount);
  }
  const auto refs = f.triangleRefs();
  for (uint64_t s = 0; s < h.surfaceVoxelCount; ++s)
    for (uint32_t r = starts[s]; r < starts[s + 1]; ++r)
      if (refs[r] >= h.triangleCount || (r > starts[s] && refs[r] <= refs[r - 1]))
        return makeError(ErrorCode::kCorrupt, f.path(), ": section TRID: entry ", r,
                         " names triangle ", refs[r], " (not ascending, or not in the table of ",
                         h.triangleCount, ")");
  return Status::ok();
}

}  // namespace

// The version 2.1 counts: zero unless the file has fragment lists; then each surface voxel has
// 1..kMaxFragmentsPerVoxel entries.
Status checkFragmentCounts(const FileHeader& h, const std::string& where) {
  const auto mode = static_cast<SurfaceMode>(h.surfaceMode);
  if (mode != SurfaceMode::kMean && mode != SurfaceMode::kPlanes && mode != SurfaceMode::kTriangles)
    return makeError(ErrorCode::kUnsupported, where, ": header.surfaceMode: ", h.surfaceMode,
                     " is not a known surface mode (0 mean, 1 planes, 2 triangles)");
  if (mode == SurfaceMode::kMean) {
    if (h.triangleCount || h.fragmentCount)
      return makeError(ErrorCode::kCorrupt, where,
                       ": header.triangleCount/fragmentCount: not zero with surfaceMode 0");
    return Status::ok();
  }
  if (h.versionMinor < kVersionMinorFragments)
    return makeError(ErrorCode::kCorrupt, where, ": header.versionMinor: ", h.versionMinor,
                     " but surfaceMode ", h.surfaceMode, " needs version 2.",
                     kVersionMinorFragments);
  if (h.fragmentCount < h.surfaceVoxelCount ||
      h.fragmentCount > h.surfaceVoxelCount * kMaxFragmentsPerVoxel || h.fragmentCount > kMaxVoxels)
    return makeError(ErrorCode::kCorrupt, where, ": header.fragmentCount: ", h.fragmentCount,
                     " does not give the ", h.surfaceVoxelCount, " surface voxels 1..",
                     kMaxFragmentsPerVoxel, " fragments each");
  // Triangles come with surface voxels: a triangles file of a scene without meshes (only
  // spheres or a volume) has neither.
  if (mode == SurfaceMode::kTriangles ? (h.surfaceVoxelCount > 0) != (h.triangleCount > 0)
                                      : h.triangleCount > 0)
    return makeError(ErrorCode::kCorrupt, where, ": header.triangleCount: ", h.triangleCount,
                     " with surfaceMode ", h.surfaceMode);
  return Status::ok();
}

Status checkFragmentLists(const VoxLinkFile& f) {
  const FileHeader& h = f.header();
  if (f.surfaceMode() == SurfaceMode::kMean) return Status::ok();
  const auto starts = f.fragmentStarts();
  if (starts[0] != 0 || starts[h.surfaceVoxelCount] != h.fragmentCount)
    return makeError(ErrorCode::kCorrupt, f.path(), ": section FROF: first/last entries ",
                     starts[0], "/", starts[h.surfaceVoxelCount], " (expected 0/", h.fragmentCount,
                     ")");
  for (uint64_t s = 0; s < h.surfaceVoxelCount; ++s) {
    const uint32_t begin = starts[s], end = starts[s + 1];
    if (end <= begin || end > h.fragmentCount || end - begin > kMaxFragmentsPerVoxel)
      return makeError(ErrorCode::kCorrupt, f.path(), ": section FROF: surface voxel ", s,
                       " has fragments [", begin, ", ", end, ") of ", h.fragmentCount,
                       " (a surface voxel has 1 to ", kMaxFragmentsPerVoxel, ")");
  }
  return f.surfaceMode() == SurfaceMode::kPlanes ? checkPlanes(f) : checkTriangles(f, starts);
}

}  // namespace voxlink::format
