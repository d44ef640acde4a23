// SPDX-License-Identifier: BSD-3-Clause
#include "geometry/sphere_voxelizer.h"

#include <algorithm>
#include <atomic>
#include <cmath>

#include "base/parallel_for.h"

namespace voxlink::geometry {
namespace {

#pragma pack(push, 4)
struct Overlap {
  uint64_t key;
  uint32_t sphere;
  bool operator<(const Overlap& o) const { return key != o.key ? key < o.key : sphere < o.sphere; }
};
#pragma pack(pop)

}  // namespace

Result<SphereVoxelization> voxelizeSpheres(const std::vector<Sphere>& spheres,
                                           const VoxelGrid& grid, uint64_t maxOverlaps,
                                           SphereFill fill, ZSlab slab) {
  VOXLINK_RETURN_IF_ERROR(validateGrid(grid));
  for (size_t s = 0; s < spheres.size(); ++s) {
    const Sphere& sphere = spheres[s];
    if (!std::isfinite(sphere.center[0]) || !std::isfinite(sphere.center[1]) ||
        !std::isfinite(sphere.center[2])) {
      return makeError(ErrorCode::kNonFinite, "sphere ", s, ": centre is not finite");
    }
    if (!(std::isfinite(sphere.radius) && sphere.radius > 0.0f)) {
      return makeError(ErrorCode::kInvalidArgument, "sphere ", s, ": radius ", sphere.radius,
                       " is not a positive finite size");
    }
  }
  if (spheres.size() > UINT32_MAX)
    return makeError(ErrorCode::kTooLarge, "spheres: ", spheres.size(), " is more than 2^32-1");

  const unsigned workers = base::threadCount(0);
  std::vector<std::vector<Overlap>> local(workers);  // one per worker
  std::atomic<uint64_t> total{0};
  std::atomic<bool> tooMany{false};
  constexpr size_t kSpheresPerItem = 64;
  const size_t items = (spheres.size() + kSpheresPerItem - 1) / kSpheresPerItem;
  base::parallelFor(items, workers, [&](uint64_t item, unsigned worker) {
    std::vector<Overlap>& out = local[worker];
    const size_t before = out.size();
    const size_t end = std::min(spheres.size(), (item + 1) * kSpheresPerItem);
    for (size_t s = item * kSpheresPerItem; s != end && !tooMany; ++s) {
      const Sphere& sphere = spheres[s];
      const auto c = grid.toGrid(sphere.center[0], sphere.center[1], sphere.center[2]);
      const double r = sphere.radius / grid.spacing;
      int64_t lo[3], hi[3];
      bool empty = false;
      for (int a = 0; a < 3; ++a) {
        // Voxel i's box [i, i+1] reaches the sphere's extent [c - r, c + r].
        lo[a] = std::max<int64_t>(0, int64_t(std::ceil(c[a] - r)) - 1);
        hi[a] = std::min<int64_t>(int64_t(grid.dims[a]) - 1, int64_t(std::floor(c[a] + r)));
      }
      lo[2] = std::max<int64_t>(lo[2], slab.begin);
      hi[2] = std::min<int64_t>(hi[2], int64_t(slab.end) - 1);
      for (int a = 0; a < 3; ++a) empty |= lo[a] > hi[a];
      if (empty) continue;
      for (int64_t k = lo[2]; k <= hi[2]; ++k) {
        for (int64_t j = lo[1]; j <= hi[1]; ++j) {
          // Candidate x range of this row from the remaining radius, widened by one voxel
          // against rounding; each candidate gets the exact test.
          const double dz = std::max({0.0, double(k) - c[2], c[2] - double(k + 1)});
          const double dy = std::max({0.0, double(j) - c[1], c[1] - double(j + 1)});
          const double rest = r * r - dy * dy - dz * dz;
          if (rest < 0.0) continue;
          const double t = std::sqrt(rest);
          const int64_t from = std::max<int64_t>(lo[0], int64_t(std::ceil(c[0] - t)) - 2);
          const int64_t to = std::min<int64_t>(hi[0], int64_t(std::floor(c[0] + t)) + 1);
          for (int64_t i = from; i <= to; ++i) {
            const bool marked = fill == SphereFill::kShell ? sphereSurfaceInVoxel(c, r, i, j, k)
                                                           : sphereOverlapsVoxel(c, r, i, j, k);
            if (marked)
              out.push_back({voxelKey(uint32_t(i), uint32_t(j), uint32_t(k)), uint32_t(s)});
          }
        }
      }
    }
    if (total.fetch_add(out.size() - before) + (out.size() - before) > maxOverlaps) tooMany = true;
  });
  if (tooMany) {
    return makeError(ErrorCode::kTooLarge, "sphere voxelizer: more than ", maxOverlaps,
                     " voxel/sphere overlaps at grid ", grid.dims[0], "x", grid.dims[1], "x",
                     grid.dims[2]);
  }
  std::vector<Overlap> overlaps;
  overlaps.reserve(total);
  for (auto& part : local) {
    overlaps.insert(overlaps.end(), part.begin(), part.end());
    std::vector<Overlap>().swap(part);
  }
  base::parallelSort(overlaps.begin(), overlaps.end());

  SphereVoxelization result;
  result.sphereIds.resize(overlaps.size());
  result.offsets.push_back(0);
  for (size_t i = 0; i < overlaps.size(); ++i) {
    if (i > 0 && overlaps[i].key != overlaps[i - 1].key) result.offsets.push_back(i);
    if (i == 0 || overlaps[i].key != overlaps[i - 1].key)
      result.voxels.push_back(voxelFromKey(overlaps[i].key));
    result.sphereIds[i] = overlaps[i].sphere;
  }
  if (!overlaps.empty()) result.offsets.push_back(overlaps.size());
  return result;
}

}  // namespace voxlink::geometry
