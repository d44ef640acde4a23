// SPDX-License-Identifier: BSD-3-Clause
#include "render/dense_volume.h"

#include <algorithm>
#include <cstring>

#include "base/process_memory.h"

namespace voxlink::render {
namespace {

// Difference along one axis at integer position i of n, in value per voxel step.
template <class Get>
double axisDifference(uint32_t i, uint32_t n, double spacing, Get get) {
  if (n < 2) return 0.0;
  if (i == 0) return (get(1) - get(0)) / spacing;
  if (i == n - 1) return (get(int(n) - 1) - get(int(n) - 2)) / spacing;
  return (get(int(i) + 1) - get(int(i) - 1)) / (2.0 * spacing);
}

}  // namespace

glm::dvec3 DenseVolume::gradient(uint32_t x, uint32_t y, uint32_t z) const {
  return {axisDifference(x, dims[0], spacing[0], [&](int i) { return at(uint32_t(i), y, z); }),
          axisDifference(y, dims[1], spacing[1], [&](int i) { return at(x, uint32_t(i), z); }),
          axisDifference(z, dims[2], spacing[2], [&](int i) { return at(x, y, uint32_t(i)); })};
}

Box DenseVolume::worldBox() const {
  Box b;
  for (int a = 0; a < 3; ++a) {
    b.lo[a] = origin[a] - 0.5 * spacing[a];
    b.hi[a] = origin[a] + (double(dims[a]) - 0.5) * spacing[a];
  }
  return b;
}

double DenseVolume::minSpacing() const { return std::min({spacing[0], spacing[1], spacing[2]}); }

Result<DenseVolume> loadDenseVolume(sources::VolumeSource& source) {
  const sources::VolumeInfo& info = source.info();
  // The source's bytes and a float64 per voxel at once. Refused before reading: Linux
  // overcommits, so an allocation beyond memory succeeds and the OOM killer ends the process
  // once the values are written.
  const uint64_t needed = info.voxelCount() * (scalarSize(info.type) + sizeof(double));
  if (needed > base::memoryForThisProcess())
    return makeError(ErrorCode::kTooLarge, info.path, ": the dense volume needs ", needed,
                     " bytes (", info.dims[0], " x ", info.dims[1], " x ", info.dims[2],
                     " voxels as ", scalarName(info.type), " and float64), more than the ",
                     base::memoryForThisProcess(), " bytes this process may use");
  VOXLINK_ASSIGN_OR_RETURN(std::vector<uint8_t> bytes, sources::readAll(source));
  DenseVolume v;
  v.dims = info.dims;
  v.spacing = info.spacing;
  v.origin = info.origin;
  v.sourceType = info.type;
  try {
    v.values.resize(info.voxelCount());
  } catch (const std::bad_alloc&) {
    return makeError(ErrorCode::kTooLarge, info.path, ": ", info.voxelCount(),
                     " float64 values do not fit in memory");
  }
  dispatchScalar(info.type, [&](auto zero) {
    using T = decltype(zero);
    for (size_t i = 0; i < v.values.size(); ++i) {
      T value;
      std::memcpy(&value, bytes.data() + i * sizeof(T), sizeof(T));
      v.values[i] = static_cast<double>(value);
    }
  });
  return v;
}

Result<DenseVolume> loadDenseVolume(const std::string& path, const sources::OpenOptions& options) {
  VOXLINK_ASSIGN_OR_RETURN(auto source, sources::openVolume(path, options));
  return loadDenseVolume(*source);
}

}  // namespace voxlink::render
