// SPDX-License-Identifier: BSD-3-Clause
#include "format/bricked_volume.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>

#include "format/brick_rows.h"
#include "format/voxlink_file.h"

namespace voxlink::format {
namespace {

uint64_t ceilDiv(uint64_t a, uint64_t b) { return (a + b - 1) / b; }

}  // namespace

std::vector<uint32_t> rankFromOccupancy(const std::vector<uint32_t>& occupancy) {
  std::vector<uint32_t> rank(occupancy.size());
  uint32_t total = 0;
  for (size_t w = 0; w < occupancy.size(); ++w) {
    rank[w] = total;
    total += static_cast<uint32_t>(std::popcount(occupancy[w]));
  }
  return rank;
}

void makeSceneHeader(FileHeader& h, const SceneSections& scene) {
  h.versionMajor = kVersionMajorScene;
  h.materialCount = static_cast<uint32_t>(scene.materials.size());
  h.sphereCount = static_cast<uint32_t>(scene.spheres.size());
  h.sphereRefCount = scene.sphereRefs.size();
  auto bits = [](const std::vector<uint32_t>& mask) {
    uint64_t n = 0;
    for (uint32_t w : mask) n += static_cast<uint64_t>(std::popcount(w));
    return n;
  };
  h.surfaceVoxelCount = bits(scene.surfaceMask);
  h.volumeVoxelCount = bits(scene.volumeMask);
  h.sphereVoxelCount = bits(scene.sphereMask);
  h.surfaceMode = static_cast<uint32_t>(scene.surfaceMode);
  if (scene.surfaceMode != SurfaceMode::kMean) {
    // Planes carry extents (2.2); triangle lists are as in 2.1.
    h.versionMinor =
        scene.surfaceMode == SurfaceMode::kPlanes ? kVersionMinorExtents : kVersionMinorFragments;
    h.fragmentCount = scene.surfaceMode == SurfaceMode::kPlanes ? scene.fragments.size()
                                                                : scene.triangleRefs.size();
    h.triangleCount = static_cast<uint32_t>(scene.triangles.size());
  }
}

Status writeBrickedVolume(const std::string& path, const BrickedVolume& v) {
  VOXLINK_RETURN_IF_ERROR(checkDescription(v.description));
  FileHeader header = makeHeader(v.description, v.voxelCount(), v.occupiedBrickCount());
  if (v.scene) {
    const SceneSections& s = *v.scene;
    const uint64_t maskWords = ceilDiv(v.voxelCount(), 32);
    if (s.volumeMask.size() != maskWords || s.surfaceMask.size() != maskWords ||
        (!s.spheres.empty() && s.sphereMask.size() != maskWords))
      return makeError(ErrorCode::kInvalidArgument, path, ": scene masks do not match the ",
                       v.voxelCount(), " voxels");
    if (s.materials.size() > kMaxMaterials)
      return makeError(ErrorCode::kTooLarge, path, ": ", s.materials.size(),
                       " materials exceed the format's limit of ", kMaxMaterials);
    if (s.triangles.size() > kMaxVoxels)
      return makeError(ErrorCode::kTooLarge, path, ": ", s.triangles.size(),
                       " triangles exceed the format's limit of ", kMaxVoxels);
    makeSceneHeader(header, s);
    if (s.surface.size() != header.surfaceVoxelCount ||
        (!s.spheres.empty() && s.sphereRefStart.size() != header.sphereVoxelCount + 1) ||
        (s.surfaceMode != SurfaceMode::kMean &&
         s.fragmentStart.size() != header.surfaceVoxelCount + 1))
      return makeError(ErrorCode::kInvalidArgument, path,
                       ": scene payloads do not match their masks");
  }
  const uint64_t slots = sampleSlots(header);
  const size_t valueBytes = slots * storedSize(v.description.valueType);
  if (v.values.size() != valueBytes || v.gradients.size() != slots)
    return makeError(ErrorCode::kInvalidArgument, path, ": VALU/GRAD hold ", v.values.size(),
                     " bytes/", v.gradients.size(), " codes, ", slots, " samples need ", valueBytes,
                     "/", slots);
  VOXLINK_ASSIGN_OR_RETURN(FileWriter writer, FileWriter::create(path, header));
  auto put = [&](SectionId id, const auto& vec) {
    using T = typename std::decay_t<decltype(vec)>::value_type;
    return writer.write(id, 0, vec.data(), vec.size() * sizeof(T));
  };
  VOXLINK_RETURN_IF_ERROR(put(SectionId::kBrickOccupancy, v.occupancy));
  VOXLINK_RETURN_IF_ERROR(put(SectionId::kBrickRank, v.rank));
  VOXLINK_RETURN_IF_ERROR(put(SectionId::kBrickVoxelBase, v.voxelBase));
  VOXLINK_RETURN_IF_ERROR(put(SectionId::kRowStart, v.rowStarts));
  VOXLINK_RETURN_IF_ERROR(put(SectionId::kRowMask, v.rowMasks));
  VOXLINK_RETURN_IF_ERROR(put(SectionId::kValues, v.values));
  VOXLINK_RETURN_IF_ERROR(put(SectionId::kGradients, v.gradients));
  if (v.scene) {
    const SceneSections& s = *v.scene;
    VOXLINK_RETURN_IF_ERROR(put(SectionId::kMaterials, s.materials));
    VOXLINK_RETURN_IF_ERROR(put(SectionId::kVolumeMask, s.volumeMask));
    VOXLINK_RETURN_IF_ERROR(put(SectionId::kSurfaceMask, s.surfaceMask));
    VOXLINK_RETURN_IF_ERROR(put(SectionId::kSurface, s.surface));
    if (!s.spheres.empty()) {
      VOXLINK_RETURN_IF_ERROR(put(SectionId::kSpheres, s.spheres));
      VOXLINK_RETURN_IF_ERROR(put(SectionId::kSphereMask, s.sphereMask));
      VOXLINK_RETURN_IF_ERROR(put(SectionId::kSphereRefStart, s.sphereRefStart));
      VOXLINK_RETURN_IF_ERROR(put(SectionId::kSphereRefs, s.sphereRefs));
    }
    if (s.surfaceMode != SurfaceMode::kMean)
      VOXLINK_RETURN_IF_ERROR(put(SectionId::kFragmentStart, s.fragmentStart));
    if (s.surfaceMode == SurfaceMode::kPlanes)
      VOXLINK_RETURN_IF_ERROR(put(SectionId::kFragments, s.fragments));
    if (s.surfaceMode == SurfaceMode::kTriangles) {
      VOXLINK_RETURN_IF_ERROR(put(SectionId::kTriangleRefs, s.triangleRefs));
      VOXLINK_RETURN_IF_ERROR(put(SectionId::kTriangles, s.triangles));
    }
  }
  return writer.commit(v.metaJson);
}

uint64_t fileOrderKey(const VolumeDescription& d, uint32_t x, uint32_t y, uint32_t z) {
  const uint32_t n = d.brickSize;
  const uint64_t gridX = ceilDiv(d.dims[0], n), gridY = ceilDiv(d.dims[1], n);
  const uint32_t p[3] = {x, y, z};
  const AxisFrame frame = axisFrame(d.predominantAxis);
  const uint64_t brick = (uint64_t{z / n} * gridY + y / n) * gridX + x / n;
  const uint32_t row = (p[frame.v] % n) * n + p[frame.u] % n;
  const uint32_t depth = p[frame.w] % n;
  return (brick * n * n + row) * n + depth;
}

BrickedVolumeBuilder::BrickedVolumeBuilder(VolumeDescription description)
    : description_(std::move(description)) {}

void BrickedVolumeBuilder::add(uint32_t x, uint32_t y, uint32_t z, uint32_t storedBits,
                               uint16_t gradient) {
  voxels_.push_back(Entry{0, storedBits, gradient, x, y, z});
}

Result<BrickedVolume> BrickedVolumeBuilder::build(std::string metaJson) const {
  VOXLINK_RETURN_IF_ERROR(checkDescription(description_));
  const VolumeDescription& d = description_;
  const uint32_t n = d.brickSize;
  const uint32_t grid[3] = {static_cast<uint32_t>(ceilDiv(d.dims[0], n)),
                            static_cast<uint32_t>(ceilDiv(d.dims[1], n)),
                            static_cast<uint32_t>(ceilDiv(d.dims[2], n))};
  const uint64_t bricks = uint64_t{grid[0]} * grid[1] * grid[2];
  std::vector<Entry> sorted = voxels_;
  for (Entry& e : sorted) {
    if (e.x >= d.dims[0] || e.y >= d.dims[1] || e.z >= d.dims[2])
      return makeError(ErrorCode::kInvalidArgument, "voxel (", e.x, ", ", e.y, ", ", e.z,
                       ") lies outside the ", d.dims[0], "x", d.dims[1], "x", d.dims[2], " volume");
    e.key = fileOrderKey(d, e.x, e.y, e.z);
  }
  std::sort(sorted.begin(), sorted.end(),
            [](const Entry& a, const Entry& b) { return a.key < b.key; });
  for (size_t i = 1; i < sorted.size(); ++i)
    if (sorted[i].key == sorted[i - 1].key)
      return makeError(ErrorCode::kInvalidArgument, "voxel (", sorted[i].x, ", ", sorted[i].y, ", ",
                       sorted[i].z, ") added twice");

  BrickedVolume v;
  v.description = d;
  v.metaJson = std::move(metaJson);
  v.occupancy.assign(ceilDiv(bricks, 32), 0);
  const size_t valueSize = storedSize(d.valueType);
  const uint32_t maskWords = maskWordsPerBrick(n);
  v.values.resize(sorted.size() * valueSize);
  v.gradients.resize(sorted.size());
  uint64_t currentBrick = UINT64_MAX;
  for (size_t i = 0; i < sorted.size(); ++i) {
    const Entry& e = sorted[i];
    const uint64_t brick = e.key / (uint64_t{n} * n * n);
    const uint32_t cell = static_cast<uint32_t>(e.key % (uint64_t{n} * n * n));  // row*n + depth
    if (brick != currentBrick) {
      currentBrick = brick;
      v.occupancy[brick / 32] |= 1u << (brick % 32);
      v.voxelBase.push_back(static_cast<uint32_t>(i));
      v.rowMasks.resize(v.rowMasks.size() + maskWords, 0);
    }
    uint32_t* mask = v.rowMasks.data() + v.rowMasks.size() - maskWords;
    mask[cell / 32] |= 1u << (cell % 32);
    std::memcpy(v.values.data() + i * valueSize, &e.bits, valueSize);  // little-endian host
    v.gradients[i] = e.gradient;
  }
  v.voxelBase.push_back(static_cast<uint32_t>(sorted.size()));
  v.rank = rankFromOccupancy(v.occupancy);
  const uint64_t k = v.occupiedBrickCount();
  v.rowStarts.resize(k * n * n);
  for (uint64_t b = 0; b < k; ++b)
    rowStartsFromMasks(v.rowMasks.data() + b * maskWords, n, v.rowStarts.data() + b * n * n);
  // Value range in source units, for the header.
  if (!sorted.empty()) {
    double lo = INFINITY, hi = -INFINITY;
    for (size_t i = 0; i < sorted.size(); ++i) {
      const double stored = storedBitsValue(d.valueType, sorted[i].bits);
      const double value = stored * d.valueScale + d.valueOffset;
      lo = std::min(lo, value);
      hi = std::max(hi, value);
    }
    v.description.valueMin = lo;
    v.description.valueMax = hi;
  }
  return v;
}

}  // namespace voxlink::format
