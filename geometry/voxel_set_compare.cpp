// SPDX-License-Identifier: BSD-3-Clause
#include "geometry/voxel_set_compare.h"

#include <algorithm>
#include <cmath>

namespace voxlink::geometry {

VoxelSetComparison compareSurfaceVoxels(const std::vector<SurfaceVoxel>& reference,
                                        const std::vector<SurfaceVoxel>& candidate) {
  VoxelSetComparison c;
  c.reference = reference.size();
  c.candidate = candidate.size();
  std::vector<double> angles;
  size_t i = 0, j = 0;
  while (i < reference.size() || j < candidate.size()) {
    const uint64_t a = i < reference.size()
                           ? voxelKey(reference[i].x, reference[i].y, reference[i].z)
                           : UINT64_MAX;
    const uint64_t b = j < candidate.size()
                           ? voxelKey(candidate[j].x, candidate[j].y, candidate[j].z)
                           : UINT64_MAX;
    if (a < b) {
      ++c.missing;
      ++i;
    } else if (b < a) {
      ++c.extra;
      ++j;
    } else {
      const auto& n = reference[i].normal;
      const auto& m = candidate[j].normal;
      const double cosine =
          std::clamp(double(n[0]) * m[0] + double(n[1]) * m[1] + double(n[2]) * m[2], -1.0, 1.0);
      angles.push_back(std::acos(cosine) * (180.0 / 3.14159265358979323846));
      c.materialMismatches += reference[i].material != candidate[j].material;
      ++c.common;
      ++i;
      ++j;
    }
  }
  if (!angles.empty()) {
    double sum = 0.0;
    for (double d : angles) sum += d;
    c.normalMeanDegrees = sum / double(angles.size());
    const size_t rank = (angles.size() * 95 + 99) / 100 - 1;
    std::nth_element(angles.begin(), angles.begin() + long(rank), angles.end());
    c.normalP95Degrees = angles[rank];
    c.normalMaxDegrees = *std::max_element(angles.begin(), angles.end());
  }
  return c;
}

}  // namespace voxlink::geometry
