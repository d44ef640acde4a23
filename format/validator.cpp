// SPDX-License-Identifier: BSD-3-Clause
#include "format/validator.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <nlohmann/json.hpp>
#include <span>
#include <vector>

#include "base/crc32c.h"
#include "base/parallel_for.h"
#include "format/brick_rows.h"
#include "format/detail/fragment_validator.h"
#include "format/gradient_codec.h"
#include "format/half.h"

namespace voxlink::format {
namespace {

// Bytes after `used` up to the section's end must be zero (padding).
Status checkPadding(const VoxLinkFile& f, SectionId id, uint64_t used) {
  auto bytes = f.sectionBytes(id);
  for (uint64_t i = used; i < bytes.size(); ++i)
    if (bytes[i] != 0)
      return makeError(ErrorCode::kCorrupt, f.path(), ": section ", sectionName(id),
                       ": padding byte ", i, " is not zero");
  return Status::ok();
}

// The first mismatch in table order is the one reported.
Status checkChecksums(const VoxLinkFile& f, ValidationReport& report) {
  const auto& sections = f.sectionTable();
  const std::vector<uint32_t> crcs = sectionChecksums(f);
  for (size_t i = 0; i < sections.size(); ++i) {
    const SectionEntry& e = sections[i];
    if (crcs[i] != e.crc)
      return makeError(
          ErrorCode::kCorrupt, f.path(), ": section ", sectionName(static_cast<SectionId>(e.id)),
          ".crc: checksum mismatch (stored 0x", std::hex, e.crc, ", computed 0x", crcs[i], ")");
    report.bytesChecked += f.sectionBytes(e).size();
  }
  return Status::ok();
}

Status checkBrickLevel(const VoxLinkFile& f) {
  const auto occupancy = f.occupancyWords();
  const auto rank = f.rankWords();
  const uint64_t bricks = f.gridBrickCount();
  uint64_t total = 0;
  for (size_t w = 0; w < occupancy.size(); ++w) {
    if (rank[w] != total)
      return makeError(ErrorCode::kCorrupt, f.path(), ": section BRNK: word ", w, " is ", rank[w],
                       ", expected ", total, " occupied bricks before it");
    total += static_cast<uint64_t>(std::popcount(occupancy[w]));
  }
  const uint64_t tailBits = occupancy.size() * 32 - bricks;
  if (tailBits > 0 && (occupancy.back() >> (32 - tailBits)) != 0)
    return makeError(ErrorCode::kCorrupt, f.path(), ": section BOCC: bits set beyond the last of ",
                     bricks, " bricks");
  if (total != f.occupiedBrickCount())
    return makeError(ErrorCode::kCorrupt, f.path(), ": section BOCC: ", total,
                     " bricks marked occupied, header.occupiedBrickCount says ",
                     f.occupiedBrickCount());
  return Status::ok();
}

Status checkBricks(const VoxLinkFile& f, ValidationReport& report,
                   const ProgressCallback& progress = {}) {
  const FileHeader& h = f.header();
  const uint32_t n = h.brickSize;
  const uint32_t maskWords = maskWordsPerBrick(n);
  const auto base = f.brickVoxelBase();
  const auto rows = f.rowStarts();
  const auto masks = f.rowMaskWords();
  const auto occupancy = f.occupancyWords();
  const AxisFrame frame = axisFrame(f.predominantAxis());
  if (base[0] != 0)
    return makeError(ErrorCode::kCorrupt, f.path(), ": section BVOX: entry 0 is ", base[0],
                     ", expected 0");
  if (base[f.occupiedBrickCount()] != f.voxelCount())
    return makeError(ErrorCode::kCorrupt, f.path(), ": section BVOX: last entry is ",
                     base[f.occupiedBrickCount()], ", header.voxelCount is ", f.voxelCount());
  std::vector<uint16_t> expectedRows(uint64_t{n} * n);
  uint64_t k = 0;
  const uint64_t reportEvery = std::max<uint64_t>(1, f.gridBrickCount() / 16);
  uint64_t nextReport = reportEvery;
  for (uint64_t b = 0; b < f.gridBrickCount(); ++b) {
    if (b >= nextReport) {
      reportProgress(progress, double(b) / double(f.gridBrickCount()), "bricks");
      nextReport = b + reportEvery;
    }
    if (occupancy[b >> 5] == 0) {  // 32 empty bricks: a sparse grid costs a read per 32
      b |= 31;
      continue;
    }
    if (((occupancy[b >> 5] >> (b & 31)) & 1u) == 0) continue;
    if (base[k + 1] <= base[k])
      return makeError(ErrorCode::kCorrupt, f.path(), ": section BVOX: occupied brick ", k,
                       " (brick ", b, ") holds no voxels");
    const uint32_t* mask = masks.data() + k * maskWords;
    const uint32_t count = rowStartsFromMasks(mask, n, expectedRows.data());
    if (count != base[k + 1] - base[k])
      return makeError(ErrorCode::kCorrupt, f.path(), ": section MASK: brick ", b, " has ", count,
                       " voxel bits, BVOX gives it ", base[k + 1] - base[k], " voxels");
    if (std::memcmp(expectedRows.data(), rows.data() + k * n * n, expectedRows.size() * 2) != 0)
      return makeError(ErrorCode::kCorrupt, f.path(), ": section ROWS: row starts of brick ", b,
                       " disagree with its MASK bits");
    // Cells outside the volume (edge bricks) must be empty.
    const uint32_t origin[3] = {
        static_cast<uint32_t>(b % h.brickGrid[0]) * n,
        static_cast<uint32_t>(b / h.brickGrid[0] % h.brickGrid[1]) * n,
        static_cast<uint32_t>(b / (uint64_t{h.brickGrid[0]} * h.brickGrid[1])) * n};
    const uint32_t extent[3] = {std::min(n, h.dims[0] - origin[0]),
                                std::min(n, h.dims[1] - origin[1]),
                                std::min(n, h.dims[2] - origin[2])};
    if (extent[0] < n || extent[1] < n || extent[2] < n) {
      for (uint32_t row = 0; row < n * n; ++row) {
        const uint32_t bits = rowBits(mask, n, row);
        if (!bits) continue;
        const bool rowInside = row % n < extent[frame.u] && row / n < extent[frame.v];
        const uint32_t depthLimit = extent[frame.w] == 32 ? ~0u : (1u << extent[frame.w]) - 1u;
        if (!rowInside || (bits & ~depthLimit))
          return makeError(ErrorCode::kCorrupt, f.path(), ": section MASK: brick ", b, " row ", row,
                           " marks voxels outside the volume");
      }
    }
    ++k;
  }
  report.bricksChecked = k;
  return Status::ok();
}

// isCanonicalGradientCode of every code, in a loop without an early exit that the compiler
// vectorizes; the loop that names the first bad code runs only when there is one.
bool allCanonical(std::span<const uint16_t> codes) {
  uint32_t bad = 0;
  for (const uint16_t c : codes) {
    const uint32_t t = c >> 8, p = c & 0xFFu;
    bad |= static_cast<uint32_t>(t == 255u && c != kZeroGradient) |
           static_cast<uint32_t>((t == 0u || t == uint32_t(kPolarSteps)) && p != 0u);
  }
  return bad == 0;
}

// For 8- and 16-bit integer values: whether every value is finite and within [lo, hi], from
// the smallest and largest stored integers alone (the mapping stored * scale + offset, rounded
// twice, never reverses the order of two integers).
template <class T>
bool integerValuesWithin(const uint8_t* bytes, uint64_t count, const FileHeader& h, double lo,
                         double hi) {
  T smallest = std::numeric_limits<T>::max(), largest = 0;
  for (uint64_t i = 0; i < count; ++i) {
    T v;
    std::memcpy(&v, bytes + i * sizeof(T), sizeof(T));
    smallest = std::min(smallest, v);
    largest = std::max(largest, v);
  }
  if (count == 0) return true;
  for (const T v : {smallest, largest}) {
    const double mapped = double(v) * h.valueScale + h.valueOffset;
    if (!std::isfinite(mapped) || mapped < lo || mapped > hi) return false;
  }
  return true;
}

// `progress` hears GRAD checked at `gradientsDone` of this stage.
Status checkVoxels(const VoxLinkFile& f, ValidationReport& report,
                   const ProgressCallback& progress = {}, double gradientsDone = 0) {
  const FileHeader& h = f.header();
  const auto grads = f.gradientCodes();
  if (!allCanonical(grads))
    for (uint64_t i = 0; i < grads.size(); ++i)
      if (!isCanonicalGradientCode(grads[i]))
        return makeError(ErrorCode::kCorrupt, f.path(), ": section GRAD: voxel ", i,
                         " has the reserved or non-canonical code 0x", std::hex, grads[i]);
  reportProgress(progress, gradientsDone, "values");
  const double slack = 1e-9 * std::max(1.0, std::max(std::abs(h.valueMin), std::abs(h.valueMax)));
  const uint64_t slots = sampleSlots(h);
  const double lo = h.valueMin - slack, hi = h.valueMax + slack;
  const bool fastPass = (f.valueType() == StoredType::kU8 &&
                         integerValuesWithin<uint8_t>(f.valueBytes(), slots, h, lo, hi)) ||
                        (f.valueType() == StoredType::kU16 &&
                         integerValuesWithin<uint16_t>(f.valueBytes(), slots, h, lo, hi));
  for (uint64_t i = 0; i < (fastPass ? 0 : slots); ++i) {
    const double v = f.value(i);
    if (!std::isfinite(v))
      return makeError(ErrorCode::kNonFinite, f.path(), ": section VALU: voxel ", i,
                       " is not finite");
    if (v < lo || v > hi)
      return makeError(ErrorCode::kCorrupt, f.path(), ": section VALU: voxel ", i, " = ", v,
                       " lies outside header.valueMin/valueMax [", h.valueMin, ", ", h.valueMax,
                       "]");
  }
  report.voxelsChecked = f.voxelCount();
  VOXLINK_RETURN_IF_ERROR(checkPadding(f, SectionId::kValues, slots * storedSize(f.valueType())));
  VOXLINK_RETURN_IF_ERROR(checkPadding(f, SectionId::kGradients, slots * 2));
  const uint64_t n = h.brickSize;
  return checkPadding(f, SectionId::kRowStart, f.occupiedBrickCount() * n * n * 2);
}

bool finiteIn(float v, float lo, float hi) { return std::isfinite(v) && v >= lo && v <= hi; }

Status checkMaterials(const VoxLinkFile& f) {
  const auto materials = f.materials();
  for (size_t m = 0; m < materials.size(); ++m) {
    const MaterialRecord& r = materials[m];
    auto bad = [&](const char* field) {
      return makeError(ErrorCode::kCorrupt, f.path(), ": section MATL: material ", m, ".", field,
                       " is out of range or not finite");
    };
    for (int c = 0; c < 3; ++c) {
      if (!finiteIn(r.color[c], 0, 1)) return bad("color");
      if (!finiteIn(r.emission[c], 0, 1e30f)) return bad("emission");
    }
    if (!finiteIn(r.opacity, 0, 1)) return bad("opacity");
    if (!finiteIn(r.reflectivity, 0, 1)) return bad("reflectivity");
    if (!finiteIn(r.transmission, 0, 1)) return bad("transmission");
    if (!finiteIn(r.reflectivity + r.transmission, 0, 1)) return bad("reflectivity+transmission");
    if (!finiteIn(r.refractiveIndex, 1, 10)) return bad("refractiveIndex");
    if (!finiteIn(r.specular, 0, 1)) return bad("specular");
    if (!finiteIn(r.shininess, 0, 1e6f)) return bad("shininess");
    for (uint32_t word : r.reserved)
      if (word != 0) return bad("reserved");
  }
  return Status::ok();
}

Status checkSpheres(const VoxLinkFile& f) {
  const auto spheres = f.spheres();
  for (size_t s = 0; s < spheres.size(); ++s) {
    const SphereRecord& r = spheres[s];
    const bool finite =
        std::isfinite(r.center[0]) && std::isfinite(r.center[1]) && std::isfinite(r.center[2]);
    if (!finite || !(std::isfinite(r.radius) && r.radius > 0))
      return makeError(ErrorCode::kCorrupt, f.path(), ": section SPHR: sphere ", s,
                       " has a centre or radius that is not finite and positive");
    if (r.material >= f.header().materialCount)
      return makeError(ErrorCode::kCorrupt, f.path(), ": section SPHR: sphere ", s, ".material ",
                       r.material, " is not in the table of ", f.header().materialCount);
    if (r.reserved[0] || r.reserved[1] || r.reserved[2])
      return makeError(ErrorCode::kCorrupt, f.path(), ": section SPHR: sphere ", s,
                       ".reserved is not zero");
  }
  return Status::ok();
}

// A mask's set bits must match its header count and stop at the last voxel.
Status checkMask(const VoxLinkFile& f, SectionId id, std::span<const uint32_t> mask, uint64_t count,
                 const char* countName) {
  uint64_t bits = 0;
  for (uint32_t w : mask) bits += static_cast<uint64_t>(std::popcount(w));
  if (bits != count)
    return makeError(ErrorCode::kCorrupt, f.path(), ": section ", sectionName(id), ": ", bits,
                     " voxels marked, header.", countName, " says ", count);
  const uint64_t tailBits = mask.size() * 32 - f.voxelCount();
  if (tailBits > 0 && (mask.back() >> (32 - tailBits)) != 0)
    return makeError(ErrorCode::kCorrupt, f.path(), ": section ", sectionName(id),
                     ": bits set beyond the last of ", f.voxelCount(), " voxels");
  return Status::ok();
}

// Masks against the header's counts, every surface word and sphere reference valid, and no
// voxel that stores nothing.
Status checkSceneVoxels(const VoxLinkFile& f) {
  const FileHeader& h = f.header();
  const bool spheres = h.sphereCount > 0;
  VOXLINK_RETURN_IF_ERROR(checkMask(f, SectionId::kVolumeMask, f.volumeMaskWords(),
                                    h.volumeVoxelCount, "volumeVoxelCount"));
  VOXLINK_RETURN_IF_ERROR(checkMask(f, SectionId::kSurfaceMask, f.surfaceMaskWords(),
                                    h.surfaceVoxelCount, "surfaceVoxelCount"));
  if (spheres)
    VOXLINK_RETURN_IF_ERROR(checkMask(f, SectionId::kSphereMask, f.sphereMaskWords(),
                                      h.sphereVoxelCount, "sphereVoxelCount"));
  const auto surface = f.surfaceWords();
  for (uint64_t s = 0; s < h.surfaceVoxelCount; ++s) {
    const uint32_t word = surface[s];
    if (surfaceMaterial(word) >= h.materialCount)
      return makeError(ErrorCode::kCorrupt, f.path(), ": section SURF: entry ", s,
                       " names material ", surfaceMaterial(word), " of ", h.materialCount);
    if (surfaceNormal(word) == kZeroGradient || !isCanonicalGradientCode(surfaceNormal(word)))
      return makeError(ErrorCode::kCorrupt, f.path(), ": section SURF: entry ", s,
                       " has the reserved or non-canonical normal code 0x", std::hex,
                       surfaceNormal(word));
  }
  if (spheres) {
    const auto refStart = f.sphereRefStarts();
    const auto refs = f.sphereRefs();
    if (refStart[0] != 0 || refStart[h.sphereVoxelCount] != h.sphereRefCount)
      return makeError(ErrorCode::kCorrupt, f.path(), ": section SROF: first/last entries ",
                       refStart[0], "/", refStart[h.sphereVoxelCount], " (expected 0/",
                       h.sphereRefCount, ")");
    for (uint64_t s = 0; s < h.sphereVoxelCount; ++s) {
      const uint32_t begin = refStart[s], end = refStart[s + 1];
      if (end <= begin || end > h.sphereRefCount)
        return makeError(ErrorCode::kCorrupt, f.path(), ": section SROF: entry ", s,
                         " references [", begin, ", ", end, ") of ", h.sphereRefCount,
                         " (a marked voxel names at least one sphere)");
      for (uint32_t r = begin; r < end; ++r)
        if (refs[r] >= h.sphereCount || (r > begin && refs[r] <= refs[r - 1]))
          return makeError(ErrorCode::kCorrupt, f.path(), ": section SRID: entry ", r,
                           " names sphere ", refs[r], " (not ascending, or not in the table of ",
                           h.sphereCount, ")");
    }
  }
  const auto volume = f.volumeMaskWords(), surfaceMask = f.surfaceMaskWords(),
             sphereMask = f.sphereMaskWords();
  for (size_t w = 0; w < volume.size(); ++w) {
    const uint64_t first = uint64_t{w} * 32,
                   inWord = std::min<uint64_t>(32, f.voxelCount() - first);
    const uint32_t present = (inWord == 32 ? ~0u : (1u << inWord) - 1u);
    const uint32_t stored = volume[w] | surfaceMask[w] | (spheres ? sphereMask[w] : 0u);
    if ((stored & present) != present)
      return makeError(ErrorCode::kCorrupt, f.path(), ": sections VMSK/SMSK/PMSK: voxel ",
                       first + std::countr_one(stored),
                       " stores nothing (no volume sample, surface or sphere)");
  }
  return Status::ok();
}

Status checkScene(const VoxLinkFile& f) {
  if (!f.isScene()) return Status::ok();
  VOXLINK_RETURN_IF_ERROR(checkMaterials(f));
  VOXLINK_RETURN_IF_ERROR(checkSpheres(f));
  VOXLINK_RETURN_IF_ERROR(checkFragmentLists(f));
  return checkSceneVoxels(f);
}

}  // namespace

Status validateStructure(const VoxLinkFile& f) {
  ValidationReport report;
  VOXLINK_RETURN_IF_ERROR(checkBrickLevel(f));
  VOXLINK_RETURN_IF_ERROR(checkBricks(f, report));
  // A scene's masks against their counts too: the gradient prediction walks VMSK slots.
  return checkScene(f);
}

std::vector<uint32_t> sectionChecksums(const VoxLinkFile& f, unsigned threads) {
  constexpr uint64_t kParallelBytes = uint64_t{8} << 20;
  const auto& sections = f.sectionTable();
  std::vector<uint32_t> crcs(sections.size());
  parallelFor(sections.size(), f.fileBytes() >= kParallelBytes ? threads : 1, [&](uint64_t i) {
    const auto bytes = f.sectionBytes(sections[i]);
    crcs[i] = crc32c(bytes.data(), bytes.size());
  });
  return crcs;
}

Result<ValidationReport> validateFile(const VoxLinkFile& f, const ProgressCallback& progress) {
  // Each stage's share of the bar is the bytes it reads: every byte for the checksums, MASK
  // and ROWS for the bricks, GRAD and VALU for the voxels.
  const double checksumBytes = double(f.fileBytes());
  const double brickBytes = double(f.sectionBytes(SectionId::kRowMask).size() +
                                   f.sectionBytes(SectionId::kRowStart).size());
  const double gradientBytes = double(f.sectionBytes(SectionId::kGradients).size());
  const double voxelBytes = gradientBytes + double(f.sectionBytes(SectionId::kValues).size());
  const double total = std::max(1.0, checksumBytes + brickBytes + voxelBytes);
  const double bricksBegin = checksumBytes / total;
  const double voxelsBegin = (checksumBytes + brickBytes) / total;
  ValidationReport report;
  reportProgress(progress, 0, "checksums");
  VOXLINK_RETURN_IF_ERROR(checkChecksums(f, report));
  reportProgress(progress, bricksBegin, "bricks");
  for (size_t i = 0; i < sizeof(f.header().reserved); ++i)
    if (f.header().reserved[i] != 0)
      return makeError(ErrorCode::kCorrupt, f.path(), ": header.reserved: byte ", i,
                       " is not zero");
  if (f.voxelCount() > 0 && !(f.header().valueMin <= f.header().valueMax))
    return makeError(ErrorCode::kCorrupt, f.path(), ": header.valueMin/valueMax: [",
                     f.header().valueMin, ", ", f.header().valueMax, "] is not a range");
  VOXLINK_RETURN_IF_ERROR(checkBrickLevel(f));
  VOXLINK_RETURN_IF_ERROR(checkBricks(f, report, progressPart(progress, bricksBegin, voxelsBegin)));
  VOXLINK_RETURN_IF_ERROR(checkScene(f));
  reportProgress(progress, voxelsBegin, "gradients");
  VOXLINK_RETURN_IF_ERROR(checkVoxels(f, report, progressPart(progress, voxelsBegin, 1.0),
                                      voxelBytes > 0 ? gradientBytes / voxelBytes : 0));
  const nlohmann::json meta =
      nlohmann::json::parse(f.metaJson(), nullptr, /*allow_exceptions=*/false);
  if (!meta.is_object())
    return makeError(ErrorCode::kCorrupt, f.path(), ": section META: not a JSON object");
  reportProgress(progress, 1.0, "validated");
  return report;
}

}  // namespace voxlink::format
