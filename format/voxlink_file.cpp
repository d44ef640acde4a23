// SPDX-License-Identifier: BSD-3-Clause
#include "format/voxlink_file.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <new>
#include <utility>
#include <vector>

#include "base/crc32c.h"
#include "format/detail/fragment_validator.h"
#include "format/half.h"

namespace voxlink::format {
namespace {

uint64_t ceilDiv(uint64_t a, uint64_t b) { return (a + b - 1) / b; }

// The version 2 counts: zero in version 1; in version 2 bounded by the voxel count.
Status checkSceneCounts(const FileHeader& h, const std::string& where) {
  if (h.versionMajor == kVersionMajor) {
    if (h.materialCount || h.sphereCount || h.sphereRefCount || h.surfaceVoxelCount ||
        h.volumeVoxelCount || h.sphereVoxelCount)
      return makeError(ErrorCode::kCorrupt, where,
                       ": header.materialCount..sphereVoxelCount: not zero in a version 1 file");
    return Status::ok();
  }
  VOXLINK_RETURN_IF_ERROR(checkFragmentCounts(h, where));
  if (h.materialCount > kMaxMaterials)
    return makeError(ErrorCode::kCorrupt, where, ": header.materialCount: ", h.materialCount,
                     " exceeds ", kMaxMaterials);
  if (h.surfaceVoxelCount > h.voxelCount || h.volumeVoxelCount > h.voxelCount ||
      h.sphereVoxelCount > h.voxelCount)
    return makeError(
        ErrorCode::kCorrupt, where,
        ": header.surfaceVoxelCount/volumeVoxelCount/sphereVoxelCount: ", h.surfaceVoxelCount, "/",
        h.volumeVoxelCount, "/", h.sphereVoxelCount, " exceed header.voxelCount ", h.voxelCount);
  if (h.sphereCount == 0 && h.sphereVoxelCount != 0)
    return makeError(ErrorCode::kCorrupt, where, ": header.sphereVoxelCount: ", h.sphereVoxelCount,
                     " voxels reference no spheres");
  if (h.surfaceVoxelCount > 0 && h.materialCount == 0)
    return makeError(ErrorCode::kCorrupt, where, ": header.materialCount: 0, but ",
                     h.surfaceVoxelCount, " surface voxels need materials");
  if (h.sphereCount == 0 && h.sphereRefCount != 0)
    return makeError(ErrorCode::kCorrupt, where, ": header.sphereRefCount: ", h.sphereRefCount,
                     " references to no spheres");
  // Every sphere reference names a sphere once per voxel.
  if (h.sphereRefCount > h.voxelCount * uint64_t{h.sphereCount} || h.sphereRefCount > kMaxVoxels)
    return makeError(ErrorCode::kCorrupt, where, ": header.sphereRefCount: ", h.sphereRefCount,
                     " is more than the voxels and spheres allow");
  return Status::ok();
}

}  // namespace

uint32_t headerChecksum(const FileHeader& header) {
  FileHeader copy = header;
  copy.headerCrc = 0;
  return crc32c(&copy, sizeof(copy));
}

std::string_view sectionName(SectionId id) {
  switch (id) {
    case SectionId::kMeta:
      return "META";
    case SectionId::kBrickOccupancy:
      return "BOCC";
    case SectionId::kBrickRank:
      return "BRNK";
    case SectionId::kBrickVoxelBase:
      return "BVOX";
    case SectionId::kRowStart:
      return "ROWS";
    case SectionId::kRowMask:
      return "MASK";
    case SectionId::kValues:
      return "VALU";
    case SectionId::kGradients:
      return "GRAD";
    case SectionId::kMaterials:
      return "MATL";
    case SectionId::kSurface:
      return "SURF";
    case SectionId::kVolumeMask:
      return "VMSK";
    case SectionId::kSurfaceMask:
      return "SMSK";
    case SectionId::kSphereMask:
      return "PMSK";
    case SectionId::kSpheres:
      return "SPHR";
    case SectionId::kSphereRefStart:
      return "SROF";
    case SectionId::kSphereRefs:
      return "SRID";
    case SectionId::kFragmentStart:
      return "FROF";
    case SectionId::kFragments:
      return "FRAG";
    case SectionId::kTriangleRefs:
      return "TRID";
    case SectionId::kTriangles:
      return "TRIS";
    case SectionId::kPack:
      return "PACK";
  }
  return "????";
}

uint32_t expectedElementBytes(const FileHeader& header, SectionId id) {
  switch (id) {
    case SectionId::kMeta:
      return 1;
    case SectionId::kRowStart:
    case SectionId::kGradients:
      return 2;
    case SectionId::kValues:
      return static_cast<uint32_t>(storedSize(static_cast<StoredType>(header.valueType)));
    case SectionId::kMaterials:
      return sizeof(MaterialRecord);
    case SectionId::kSpheres:
      return sizeof(SphereRecord);
    case SectionId::kFragments:
      return sizeof(FragmentRecord);
    case SectionId::kTriangles:
      return sizeof(TriangleRecord);
    default:
      return 4;
  }
}

uint64_t sampleSlots(const FileHeader& h) {
  return h.versionMajor == kVersionMajorScene ? h.volumeVoxelCount : h.voxelCount;
}

uint64_t expectedSectionBytes(const FileHeader& header, SectionId id, uint64_t metaBytes) {
  const uint64_t n = header.brickSize;
  const uint64_t bricks = uint64_t{header.brickGrid[0]} * header.brickGrid[1] * header.brickGrid[2];
  const uint64_t k = header.occupiedBrickCount;
  const uint64_t voxels = header.voxelCount;
  switch (id) {
    case SectionId::kMeta:
      return alignUp(metaBytes, 4);
    case SectionId::kBrickOccupancy:
    case SectionId::kBrickRank:
      return ceilDiv(bricks, 32) * 4;
    case SectionId::kBrickVoxelBase:
      return (k + 1) * 4;
    case SectionId::kRowStart:
      return alignUp(k * n * n * 2, 4);
    case SectionId::kRowMask:
      return k * maskWordsPerBrick(static_cast<uint32_t>(n)) * 4;
    case SectionId::kValues:
      return alignUp(sampleSlots(header) * storedSize(static_cast<StoredType>(header.valueType)),
                     4);
    case SectionId::kGradients:
      return alignUp(sampleSlots(header) * 2, 4);
    case SectionId::kMaterials:
      return uint64_t{header.materialCount} * sizeof(MaterialRecord);
    case SectionId::kVolumeMask:
    case SectionId::kSurfaceMask:
    case SectionId::kSphereMask:
      return ceilDiv(voxels, 32) * 4;
    case SectionId::kSurface:
      return header.surfaceVoxelCount * 4;
    case SectionId::kSpheres:
      return uint64_t{header.sphereCount} * sizeof(SphereRecord);
    case SectionId::kSphereRefStart:
      return (header.sphereVoxelCount + 1) * 4;
    case SectionId::kSphereRefs:
      return header.sphereRefCount * 4;
    case SectionId::kFragmentStart:
      return (header.surfaceVoxelCount + 1) * 4;
    case SectionId::kFragments:
      return header.fragmentCount * sizeof(FragmentRecord);
    case SectionId::kTriangleRefs:
      return header.fragmentCount * 4;
    case SectionId::kTriangles:
      return uint64_t{header.triangleCount} * sizeof(TriangleRecord);
    case SectionId::kPack:  // packed files only; never part of an unpacked file
      return 0;
  }
  return 0;
}

Status checkHeader(const FileHeader& h, uint64_t fileBytes, const std::string& where) {
  if (std::memcmp(h.magic, kMagic, sizeof(kMagic)) != 0)
    return makeError(ErrorCode::kNotAVoxLinkFile, where,
                     ": header.magic: not a VoxLink file (expected \"VOXLINK\\0\")");
  if (h.byteOrderMark == kByteOrderMarkSwapped)
    return makeError(ErrorCode::kByteOrder, where,
                     ": header.byteOrderMark: file was written big-endian; this reader reads "
                     "little-endian files only");
  if (h.byteOrderMark != kByteOrderMark)
    return makeError(ErrorCode::kCorrupt, where, ": header.byteOrderMark: 0x", std::hex,
                     h.byteOrderMark, " is not 0x01020304");
  if (h.versionMajor != kVersionMajor && h.versionMajor != kVersionMajorScene)
    return makeError(ErrorCode::kUnsupported, where, ": header.versionMajor: file is version ",
                     h.versionMajor, ".", h.versionMinor, ", this reader reads versions ",
                     kVersionMajor, ".x and ", kVersionMajorScene, ".x");
  if (h.headerBytes != sizeof(FileHeader))
    return makeError(ErrorCode::kCorrupt, where, ": header.headerBytes: ", h.headerBytes,
                     " (expected ", sizeof(FileHeader), ")");
  if (headerChecksum(h) != h.headerCrc)
    return makeError(ErrorCode::kCorrupt, where, ": header.headerCrc: checksum mismatch (stored 0x",
                     std::hex, h.headerCrc, ", computed 0x", headerChecksum(h), ")");
  if (!isValidBrickSize(h.brickSize))
    return makeError(ErrorCode::kCorrupt, where, ": header.brickSize: ", h.brickSize,
                     " (expected 4, 8, 16 or 32)");
  for (int a = 0; a < 3; ++a) {
    if (h.dims[a] == 0 || h.dims[a] > kMaxDim)
      return makeError(ErrorCode::kCorrupt, where, ": header.dims[", a, "]: ", h.dims[a],
                       " (expected 1..", kMaxDim, ")");
    if (h.brickGrid[a] != ceilDiv(h.dims[a], h.brickSize))
      return makeError(ErrorCode::kCorrupt, where, ": header.brickGrid[", a, "]: ", h.brickGrid[a],
                       " (expected ceil(", h.dims[a], "/", h.brickSize, "))");
    if (!(std::isfinite(h.spacing[a]) && h.spacing[a] > 0))
      return makeError(ErrorCode::kCorrupt, where, ": header.spacing[", a, "]: ", h.spacing[a],
                       " (expected a finite value > 0)");
    if (!std::isfinite(h.origin[a]))
      return makeError(ErrorCode::kCorrupt, where, ": header.origin[", a, "]: not finite");
  }
  if (h.predominantAxis > 2)
    return makeError(ErrorCode::kCorrupt, where,
                     ": header.predominantAxis: ", int(h.predominantAxis), " (expected 0, 1 or 2)");
  if (!isValidStoredType(h.valueType))
    return makeError(ErrorCode::kUnsupported, where, ": header.valueType: ", int(h.valueType),
                     " is not a known stored type");
  if (h.gradientCodec != static_cast<uint8_t>(GradientCodec::kPolar16))
    return makeError(ErrorCode::kUnsupported, where,
                     ": header.gradientCodec: ", int(h.gradientCodec),
                     " is not a known gradient codec");
  if (!isValidScalarType(h.sourceType))
    return makeError(ErrorCode::kCorrupt, where, ": header.sourceType: ", int(h.sourceType),
                     " is not a known scalar type");
  if (!std::isfinite(h.valueScale) || h.valueScale == 0 || !std::isfinite(h.valueOffset))
    return makeError(ErrorCode::kCorrupt, where,
                     ": header.valueScale/valueOffset: not a finite, invertible mapping");
  const uint64_t bricks = uint64_t{h.brickGrid[0]} * h.brickGrid[1] * h.brickGrid[2];
  const uint64_t n3 = uint64_t{h.brickSize} * h.brickSize * h.brickSize;
  if (h.occupiedBrickCount > bricks)
    return makeError(ErrorCode::kCorrupt, where,
                     ": header.occupiedBrickCount: ", h.occupiedBrickCount, " exceeds the ", bricks,
                     " bricks of the grid");
  if (h.voxelCount > kMaxVoxels || h.voxelCount > h.occupiedBrickCount * n3 ||
      h.voxelCount < h.occupiedBrickCount)
    return makeError(ErrorCode::kCorrupt, where, ": header.voxelCount: ", h.voxelCount,
                     " does not fit ", h.occupiedBrickCount, " occupied bricks of ", n3, " voxels");
  VOXLINK_RETURN_IF_ERROR(checkSceneCounts(h, where));
  if (h.sectionTableOffset > fileBytes || h.sectionCount > kMaxSectionCount ||
      h.sectionTableOffset + uint64_t{h.sectionCount} * sizeof(SectionEntry) > fileBytes)
    return makeError(ErrorCode::kTruncated, where, ": header.sectionTableOffset: table of ",
                     h.sectionCount, " entries at byte ", h.sectionTableOffset,
                     " lies beyond the end of the ", fileBytes, "-byte file");
  return Status::ok();
}

namespace {

// Every byte of a file belongs to the header, a section or the table, each preceded by less than
// kSectionAlignment bytes of padding: a file cannot carry, nor a packed file unpack to, gigabytes
// that nothing describes (the checksums cover only what the table names).
Status checkEveryByteIsDescribed(const std::vector<SectionEntry>& table, const FileHeader& h,
                                 uint64_t size, const std::string& where) {
  std::vector<std::pair<uint64_t, uint64_t>> parts = {
      {0, sizeof(FileHeader)},
      {h.sectionTableOffset, h.sectionTableOffset + table.size() * sizeof(SectionEntry)}};
  for (const SectionEntry& e : table) parts.emplace_back(e.offset, e.offset + e.bytes);
  std::sort(parts.begin(), parts.end());
  uint64_t described = 0;
  for (const auto& [begin, end] : parts) {
    if (begin >= described + kSectionAlignment)
      return makeError(ErrorCode::kCorrupt, where, ": bytes [", described, ", ", begin,
                       ") belong to no section (more than ", kSectionAlignment - 1,
                       " bytes of padding)");
    described = std::max(described, end);
  }
  if (size >= described + kSectionAlignment)
    return makeError(ErrorCode::kCorrupt, where, ": the last ", size - described, " bytes of the ",
                     size, "-byte file belong to no section");
  return Status::ok();
}

}  // namespace

Result<VoxLinkFile> VoxLinkFile::open(const std::string& path) {
  VOXLINK_ASSIGN_OR_RETURN(MappedFile mapped, MappedFile::open(path));
  auto holder = std::make_shared<MappedFile>(std::move(mapped));
  const uint8_t* data = holder->data();
  const uint64_t size = holder->size();
  return parse(std::shared_ptr<const void>(holder, holder.get()), data, size, path);
}

Result<VoxLinkFile> VoxLinkFile::read(const std::string& path) {
  VOXLINK_ASSIGN_OR_RETURN(MappedFile mapped, MappedFile::open(path));
  const std::span<const uint8_t> bytes(mapped.data(), mapped.size());
  std::vector<uint8_t> copy;
  try {
    copy.assign(bytes.begin(), bytes.end());
  } catch (const std::bad_alloc&) {
    return makeError(ErrorCode::kTooLarge, path, ": ", bytes.size(), " bytes do not fit in memory");
  }
  return fromBytes(std::move(copy), path);
}

Result<VoxLinkFile> VoxLinkFile::fromBytes(std::vector<uint8_t> bytes, const std::string& name) {
  auto holder = std::make_shared<std::vector<uint8_t>>(std::move(bytes));
  return parse(std::shared_ptr<const void>(holder, holder.get()), holder->data(), holder->size(),
               name);
}

Result<VoxLinkFile> VoxLinkFile::parseOwned(std::shared_ptr<const void> owner, const uint8_t* data,
                                            uint64_t size, std::string path, uint64_t packedBytes) {
  VOXLINK_ASSIGN_OR_RETURN(VoxLinkFile file, parse(std::move(owner), data, size, std::move(path)));
  file.packedBytes_ = packedBytes;
  return file;
}

Result<VoxLinkFile> VoxLinkFile::parse(std::shared_ptr<const void> owner, const uint8_t* data,
                                       uint64_t size, std::string path) {
  if (size < sizeof(FileHeader)) {
    if (size >= sizeof(kMagic) && std::memcmp(data, kMagic, sizeof(kMagic)) != 0)
      return makeError(ErrorCode::kNotAVoxLinkFile, path, ": header.magic: not a VoxLink file");
    return makeError(ErrorCode::kTruncated, path, ": header: file has ", size,
                     " bytes, a header needs ", sizeof(FileHeader));
  }
  if (reinterpret_cast<uintptr_t>(data) % 8 != 0)
    return makeError(ErrorCode::kInvalidArgument, path, ": buffer is not 8-byte aligned");
  VoxLinkFile file;
  file.owner_ = std::move(owner);
  file.data_ = data;
  file.size_ = size;
  file.path_ = std::move(path);
  file.header_ = reinterpret_cast<const FileHeader*>(data);
  VOXLINK_RETURN_IF_ERROR(checkHeader(*file.header_, size, file.path_));

  const FileHeader& h = *file.header_;
  file.table_.resize(h.sectionCount);
  std::memcpy(file.table_.data(), data + h.sectionTableOffset,
              h.sectionCount * sizeof(SectionEntry));
  const std::string& where = file.path_;
  for (size_t i = 0; i < file.table_.size(); ++i) {
    const SectionEntry& e = file.table_[i];
    const std::string name(sectionName(static_cast<SectionId>(e.id)));
    if (e.offset % kSectionAlignment != 0)
      return makeError(ErrorCode::kCorrupt, where, ": section ", name, ".offset: ", e.offset,
                       " is not a multiple of ", kSectionAlignment);
    if (e.offset < sizeof(FileHeader) || e.offset > size || e.bytes > size - e.offset)
      return makeError(ErrorCode::kTruncated, where, ": section ", name, ": bytes [", e.offset,
                       ", ", e.offset + e.bytes, ") lie beyond the end of the ", size,
                       "-byte file");
    if (e.bytes % 4 != 0)
      return makeError(ErrorCode::kCorrupt, where, ": section ", name, ".bytes: ", e.bytes,
                       " is not a multiple of 4");
    for (size_t j = 0; j < i; ++j) {
      const SectionEntry& o = file.table_[j];
      if (o.id == e.id)
        return makeError(ErrorCode::kCorrupt, where, ": section ", name,
                         ": appears twice in the section table");
      if (e.offset < o.offset + o.bytes && o.offset < e.offset + e.bytes)
        return makeError(ErrorCode::kCorrupt, where, ": section ", name, ": overlaps section ",
                         sectionName(static_cast<SectionId>(o.id)));
    }
  }
  VOXLINK_RETURN_IF_ERROR(checkEveryByteIsDescribed(file.table_, h, size, where));
  const SectionEntry* meta = file.findSection(SectionId::kMeta);
  for (SectionId id : kRequiredSections) {
    const SectionEntry* e = file.findSection(id);
    if (!e)
      return makeError(ErrorCode::kCorrupt, where, ": section ", sectionName(id), ": missing");
    if (e->elementBytes != expectedElementBytes(h, id))
      return makeError(ErrorCode::kCorrupt, where, ": section ", sectionName(id),
                       ".elementBytes: ", e->elementBytes, " (expected ",
                       expectedElementBytes(h, id), ")");
    if (id == SectionId::kMeta) continue;
    const uint64_t expected = expectedSectionBytes(h, id, meta->bytes);
    if (e->bytes != expected)
      return makeError(ErrorCode::kSizeMismatch, where, ": section ", sectionName(id),
                       ".bytes: ", e->bytes, " but the header's counts need ", expected);
  }
  for (SectionId id : file.presentSceneSections()) {
    const SectionEntry* e = file.findSection(id);
    if (!e)
      return makeError(ErrorCode::kCorrupt, where, ": section ", sectionName(id),
                       ": missing (a version ", h.versionMajor, " file with ", h.sphereCount,
                       " spheres has it)");
    if (e->elementBytes != expectedElementBytes(h, id))
      return makeError(ErrorCode::kCorrupt, where, ": section ", sectionName(id),
                       ".elementBytes: ", e->elementBytes, " (expected ",
                       expectedElementBytes(h, id), ")");
    const uint64_t expected = expectedSectionBytes(h, id, 0);
    if (e->bytes != expected)
      return makeError(ErrorCode::kSizeMismatch, where, ": section ", sectionName(id),
                       ".bytes: ", e->bytes, " but the header's counts need ", expected);
  }
  file.values_ = file.sectionBytes(SectionId::kValues).data();  // value(i) is hot
  return file;
}

const SectionEntry* VoxLinkFile::findSection(SectionId id) const {
  for (const SectionEntry& e : table_)
    if (e.id == static_cast<uint32_t>(id)) return &e;
  return nullptr;
}

std::span<const uint8_t> VoxLinkFile::sectionBytes(const SectionEntry& e) const {
  return {data_ + e.offset, static_cast<size_t>(e.bytes)};
}

std::span<const uint8_t> VoxLinkFile::sectionBytes(SectionId id) const {
  const SectionEntry* e = findSection(id);
  return e ? sectionBytes(*e) : std::span<const uint8_t>{};
}

std::span<const uint32_t> VoxLinkFile::words32(SectionId id) const {
  auto bytes = sectionBytes(id);
  return {reinterpret_cast<const uint32_t*>(bytes.data()), bytes.size() / 4};
}

uint64_t VoxLinkFile::gridBrickCount() const {
  return uint64_t{header_->brickGrid[0]} * header_->brickGrid[1] * header_->brickGrid[2];
}

std::span<const uint32_t> VoxLinkFile::brickVoxelBase() const {
  return words32(SectionId::kBrickVoxelBase).first(occupiedBrickCount() + 1);
}

std::span<const uint16_t> VoxLinkFile::rowStarts() const {
  auto bytes = sectionBytes(SectionId::kRowStart);
  const uint64_t n = brickSize();
  return {reinterpret_cast<const uint16_t*>(bytes.data()),
          static_cast<size_t>(occupiedBrickCount() * n * n)};
}

std::span<const uint16_t> VoxLinkFile::gradientCodes() const {
  auto bytes = sectionBytes(SectionId::kGradients);
  return {reinterpret_cast<const uint16_t*>(bytes.data()),
          static_cast<size_t>(sampleSlots(*header_))};
}

std::vector<SectionId> sceneSectionsOf(const FileHeader& h) {
  std::vector<SectionId> ids;
  if (h.versionMajor != kVersionMajorScene) return ids;
  ids.assign(kSceneSections.begin(), kSceneSections.end());
  if (h.sphereCount > 0) ids.insert(ids.end(), kSphereSections.begin(), kSphereSections.end());
  if (h.surfaceMode == uint32_t(SurfaceMode::kPlanes))
    ids.insert(ids.end(), kPlaneSections.begin(), kPlaneSections.end());
  if (h.surfaceMode == uint32_t(SurfaceMode::kTriangles))
    ids.insert(ids.end(), kTriangleSections.begin(), kTriangleSections.end());
  return ids;
}

std::vector<SectionId> VoxLinkFile::presentSceneSections() const {
  return sceneSectionsOf(*header_);
}

std::span<const MaterialRecord> VoxLinkFile::materials() const {
  auto bytes = sectionBytes(SectionId::kMaterials);
  return {reinterpret_cast<const MaterialRecord*>(bytes.data()),
          bytes.size() / sizeof(MaterialRecord)};
}

std::span<const FragmentRecord> VoxLinkFile::fragments() const {
  auto bytes = sectionBytes(SectionId::kFragments);
  return {reinterpret_cast<const FragmentRecord*>(bytes.data()),
          bytes.size() / sizeof(FragmentRecord)};
}

std::span<const TriangleRecord> VoxLinkFile::triangles() const {
  auto bytes = sectionBytes(SectionId::kTriangles);
  return {reinterpret_cast<const TriangleRecord*>(bytes.data()),
          bytes.size() / sizeof(TriangleRecord)};
}

std::span<const SphereRecord> VoxLinkFile::spheres() const {
  auto bytes = sectionBytes(SectionId::kSpheres);
  return {reinterpret_cast<const SphereRecord*>(bytes.data()), bytes.size() / sizeof(SphereRecord)};
}

std::string VoxLinkFile::metaJson() const {
  auto bytes = sectionBytes(SectionId::kMeta);
  std::string text(reinterpret_cast<const char*>(bytes.data()), bytes.size());
  while (!text.empty() && text.back() == '\0') text.pop_back();  // padding
  return text;
}

}  // namespace voxlink::format
