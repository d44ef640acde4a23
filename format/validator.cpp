#include "format/validator.h"

#include <bit>
#include <cmath>
#include <cstring>
#include <nlohmann/json.hpp>
#include <vector>

#include "format/brick_rows.h"
#include "format/crc32c.h"
#include "format/gradient_codec.h"
#include "format/half.h"

namespace voxlink::format {
namespace {

// Bytes after `used` up to the section's end must be zero (padding).
Status checkPadding(const VoxLinkFile& f, SectionId id, uint64_t used) {
  auto bytes = f.sectionBytes(id);
  for (uint64_t i = used; i < bytes.size(); ++i)
    if (bytes[i] != 0)
      return makeError(ErrorCode::kCorrupt, f.path(), ": section ", sectionName(id), ": padding byte ", i, " is not zero");
  return Status::ok();
}

Status checkChecksums(const VoxLinkFile& f, ValidationReport& report) {
  for (const SectionEntry& e : f.sectionTable()) {
    auto bytes = f.sectionBytes(e);
    const uint32_t crc = crc32c(bytes.data(), bytes.size());
    if (crc != e.crc)
      return makeError(ErrorCode::kCorrupt, f.path(), ": section ", sectionName(static_cast<SectionId>(e.id)), ".crc: checksum mismatch (stored 0x", std::hex, e.crc, ", computed 0x", crc, ")");
    report.bytesChecked += bytes.size();
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
      return makeError(ErrorCode::kCorrupt, f.path(), ": section BRNK: word ", w, " is ", rank[w], ", expected ", total, " occupied bricks before it");
    total += static_cast<uint64_t>(std::popcount(occupancy[w]));
  }
  const uint64_t tailBits = occupancy.size() * 32 - bricks;
  if (tailBits > 0 && (occupancy.back() >> (32 - tailBits)) != 0)
    return makeError(ErrorCode::kCorrupt, f.path(), ": section BOCC: bits set beyond the last of ", bricks, " bricks");
  if (total != f.occupiedBrickCount())
    return makeError(ErrorCode::kCorrupt, f.path(), ": section BOCC: ", total, " bricks marked occupied, header.occupiedBrickCount says ", f.occupiedBrickCount());
  return Status::ok();
}

Status checkBricks(const VoxLinkFile& f, ValidationReport& report) {
  const FileHeader& h = f.header();
  const uint32_t n = h.brickSize;
  const uint32_t maskWords = maskWordsPerBrick(n);
  const auto base = f.brickVoxelBase();
  const auto rows = f.rowStarts();
  const auto masks = f.rowMaskWords();
  const auto occupancy = f.occupancyWords();
  const AxisFrame frame = axisFrame(f.predominantAxis());
  if (base[0] != 0)
    return makeError(ErrorCode::kCorrupt, f.path(), ": section BVOX: entry 0 is ", base[0], ", expected 0");
  if (base[f.occupiedBrickCount()] != f.voxelCount())
    return makeError(ErrorCode::kCorrupt, f.path(), ": section BVOX: last entry is ", base[f.occupiedBrickCount()], ", header.voxelCount is ", f.voxelCount());
  std::vector<uint16_t> expectedRows(uint64_t{n} * n);
  uint64_t k = 0;
  for (uint64_t b = 0; b < f.gridBrickCount(); ++b) {
    if (((occupancy[b >> 5] >> (b & 31)) & 1u) == 0) continue;
    if (base[k + 1] <= base[k])
      return makeError(ErrorCode::kCorrupt, f.path(), ": section BVOX: occupied brick ", k, " (brick ", b, ") holds no voxels");
    const uint32_t* mask = masks.data() + k * maskWords;
    const uint32_t count = rowStartsFromMasks(mask, n, expectedRows.data());
    if (count != base[k + 1] - base[k])
      return makeError(ErrorCode::kCorrupt, f.path(), ": section MASK: brick ", b, " has ", count, " voxel bits, BVOX gives it ", base[k + 1] - base[k], " voxels");
    if (std::memcmp(expectedRows.data(), rows.data() + k * n * n, expectedRows.size() * 2) != 0)
      return makeError(ErrorCode::kCorrupt, f.path(), ": section ROWS: row starts of brick ", b, " disagree with its MASK bits");
    // Cells outside the volume (edge bricks) must be empty.
    const uint32_t origin[3] = {static_cast<uint32_t>(b % h.brickGrid[0]) * n,
                                static_cast<uint32_t>(b / h.brickGrid[0] % h.brickGrid[1]) * n,
                                static_cast<uint32_t>(b / (uint64_t{h.brickGrid[0]} * h.brickGrid[1])) * n};
    const uint32_t extent[3] = {std::min(n, h.dims[0] - origin[0]), std::min(n, h.dims[1] - origin[1]),
                                std::min(n, h.dims[2] - origin[2])};
    if (extent[0] < n || extent[1] < n || extent[2] < n) {
      for (uint32_t row = 0; row < n * n; ++row) {
        const uint32_t bits = rowBits(mask, n, row);
        if (!bits) continue;
        const bool rowInside = row % n < extent[frame.u] && row / n < extent[frame.v];
        const uint32_t depthLimit = extent[frame.w] == 32 ? ~0u : (1u << extent[frame.w]) - 1u;
        if (!rowInside || (bits & ~depthLimit))
          return makeError(ErrorCode::kCorrupt, f.path(), ": section MASK: brick ", b, " row ", row, " marks voxels outside the volume");
      }
    }
    ++k;
  }
  report.bricksChecked = k;
  return Status::ok();
}

Status checkVoxels(const VoxLinkFile& f, ValidationReport& report) {
  const FileHeader& h = f.header();
  const auto grads = f.gradientCodes();
  for (uint64_t i = 0; i < grads.size(); ++i)
    if (!isCanonicalGradientCode(grads[i]))
      return makeError(ErrorCode::kCorrupt, f.path(), ": section GRAD: voxel ", i, " has the reserved or non-canonical code 0x", std::hex, grads[i]);
  const double slack = 1e-9 * std::max(1.0, std::max(std::abs(h.valueMin), std::abs(h.valueMax)));
  for (uint64_t i = 0; i < f.voxelCount(); ++i) {
    const double v = f.value(i);
    if (!std::isfinite(v))
      return makeError(ErrorCode::kNonFinite, f.path(), ": section VALU: voxel ", i, " is not finite");
    if (v < h.valueMin - slack || v > h.valueMax + slack)
      return makeError(ErrorCode::kCorrupt, f.path(), ": section VALU: voxel ", i, " = ", v, " lies outside header.valueMin/valueMax [", h.valueMin, ", ", h.valueMax, "]");
  }
  report.voxelsChecked = f.voxelCount();
  VOXLINK_RETURN_IF_ERROR(checkPadding(f, SectionId::kValues, f.voxelCount() * storedSize(f.valueType())));
  VOXLINK_RETURN_IF_ERROR(checkPadding(f, SectionId::kGradients, f.voxelCount() * 2));
  const uint64_t n = h.brickSize;
  return checkPadding(f, SectionId::kRowStart, f.occupiedBrickCount() * n * n * 2);
}

}  // namespace

Result<VoxLinkFile> openValidatedFile(const std::string& path) {
  VOXLINK_ASSIGN_OR_RETURN(VoxLinkFile file, VoxLinkFile::open(path));
  VOXLINK_RETURN_IF_ERROR(validateFile(file).status());
  return file;
}

Result<ValidationReport> validateFile(const VoxLinkFile& f) {
  ValidationReport report;
  VOXLINK_RETURN_IF_ERROR(checkChecksums(f, report));
  for (size_t i = 0; i < sizeof(f.header().reserved); ++i)
    if (f.header().reserved[i] != 0)
      return makeError(ErrorCode::kCorrupt, f.path(), ": header.reserved: byte ", i, " is not zero");
  if (f.voxelCount() > 0 && !(f.header().valueMin <= f.header().valueMax))
    return makeError(ErrorCode::kCorrupt, f.path(), ": header.valueMin/valueMax: [", f.header().valueMin, ", ", f.header().valueMax, "] is not a range");
  VOXLINK_RETURN_IF_ERROR(checkBrickLevel(f));
  VOXLINK_RETURN_IF_ERROR(checkBricks(f, report));
  VOXLINK_RETURN_IF_ERROR(checkVoxels(f, report));
  const nlohmann::json meta = nlohmann::json::parse(f.metaJson(), nullptr, /*allow_exceptions=*/false);
  if (!meta.is_object())
    return makeError(ErrorCode::kCorrupt, f.path(), ": section META: not a JSON object");
  return report;
}

}  // namespace voxlink::format
