// SPDX-License-Identifier: BSD-3-Clause
// Read access to a VoxLink file: maps it, checks the header and the section table (cheap), and
// hands out typed views of the sections. Checksums and deep invariants are checked by
// validateFile() (format/validator.h), which reads every byte.
#pragma once

#include <cstdint>
#include <cstring>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "base/error.h"
#include "base/mapped_file.h"
#include "base/progress.h"
#include "format/half.h"
#include "format/layout.h"
#include "format/scalar_type.h"

namespace voxlink::format {

class VoxLinkFile {
 public:
  static Result<VoxLinkFile> open(const std::string& path);
  // Like open(), but the bytes are a private copy in memory instead of a mapping of the file: for
  // handles that live long (Python, ParaView), which a later in-place overwrite or truncation of
  // the file on disk must not crash (a mapping would raise SIGBUS or SIGSEGV).
  static Result<VoxLinkFile> read(const std::string& path);
  // For tests and tools that hold a file in memory; `name` is used in error messages.
  static Result<VoxLinkFile> fromBytes(std::vector<uint8_t> bytes, const std::string& name);
  // The file in `size` bytes at `data`, which `owner` keeps alive (pack/ hands over what it
  // unpacked); `packedBytes` is the size on disk of the packed file (0: not packed).
  static Result<VoxLinkFile> parseOwned(std::shared_ptr<const void> owner, const uint8_t* data,
                                        uint64_t size, std::string path, uint64_t packedBytes = 0);

  const std::string& path() const { return path_; }
  const FileHeader& header() const { return *header_; }
  uint64_t fileBytes() const { return size_; }  // unpacked
  std::span<const uint8_t> bytes() const { return {data_, size_}; }
  // Size on disk of the packed file this was unpacked from (pack/open_file.h); 0 when the
  // file was not packed.
  uint64_t packedBytes() const { return packedBytes_; }
  const std::vector<SectionEntry>& sectionTable() const { return table_; }
  const SectionEntry* findSection(SectionId id) const;
  std::span<const uint8_t> sectionBytes(SectionId id) const;
  std::span<const uint8_t> sectionBytes(const SectionEntry& entry) const;

  uint32_t brickSize() const { return header_->brickSize; }
  uint64_t gridBrickCount() const;
  uint64_t occupiedBrickCount() const { return header_->occupiedBrickCount; }
  uint64_t voxelCount() const { return header_->voxelCount; }
  Axis predominantAxis() const { return static_cast<Axis>(header_->predominantAxis); }
  StoredType valueType() const { return static_cast<StoredType>(header_->valueType); }
  ScalarType sourceType() const { return static_cast<ScalarType>(header_->sourceType); }

  std::span<const uint32_t> occupancyWords() const { return words32(SectionId::kBrickOccupancy); }
  std::span<const uint32_t> rankWords() const { return words32(SectionId::kBrickRank); }
  // K + 1 entries: voxel range of occupied brick k is [base[k], base[k+1]).
  std::span<const uint32_t> brickVoxelBase() const;
  std::span<const uint16_t> rowStarts() const;  // K * n^2
  std::span<const uint32_t> rowMaskWords() const { return words32(SectionId::kRowMask); }
  std::span<const uint16_t> gradientCodes() const;  // sampleSlots(header())
  const uint8_t* valueBytes() const { return values_; }
  std::string metaJson() const;

  // Version 2 (scene) sections; empty spans in a version 1 file.
  bool isScene() const { return header_->versionMajor == kVersionMajorScene; }
  std::vector<SectionId> presentSceneSections() const;  // the scene sections this file must have
  std::span<const MaterialRecord> materials() const;
  std::span<const uint32_t> volumeMaskWords() const { return words32(SectionId::kVolumeMask); }
  std::span<const uint32_t> surfaceMaskWords() const { return words32(SectionId::kSurfaceMask); }
  std::span<const uint32_t> surfaceWords() const {
    return words32(SectionId::kSurface);
  }  // by slot
  std::span<const SphereRecord> spheres() const;
  std::span<const uint32_t> sphereMaskWords() const { return words32(SectionId::kSphereMask); }
  std::span<const uint32_t> sphereRefStarts() const {
    return words32(SectionId::kSphereRefStart);
  }  // by slot
  std::span<const uint32_t> sphereRefs() const { return words32(SectionId::kSphereRefs); }
  // Version 2.1 fragment lists (empty spans without them): surface slot s has entries
  // [fragmentStarts()[s], fragmentStarts()[s + 1]) of fragments() or triangleRefs().
  SurfaceMode surfaceMode() const { return static_cast<SurfaceMode>(header_->surfaceMode); }
  std::span<const uint32_t> fragmentStarts() const { return words32(SectionId::kFragmentStart); }
  std::span<const FragmentRecord> fragments() const;
  std::span<const uint32_t> triangleRefs() const { return words32(SectionId::kTriangleRefs); }
  std::span<const TriangleRecord> triangles() const;
  // Per-voxel access through the masks: format/scene_index.h.

  // Value of VALU entry i in source units (stored value mapped through scale and offset). In
  // version 1 entry i is voxel i; in version 2 it is volume slot i (format/scene_index.h).
  double value(uint64_t voxel) const;
  // The stored value of voxel i as a double, before the mapping.
  double storedValue(uint64_t voxel) const;

 private:
  static Result<VoxLinkFile> parse(std::shared_ptr<const void> owner, const uint8_t* data,
                                   uint64_t size, std::string path);
  std::span<const uint32_t> words32(SectionId id) const;

  std::shared_ptr<const void> owner_;  // keeps the mapping or the byte vector alive
  const uint8_t* data_ = nullptr;
  uint64_t size_ = 0;
  std::string path_;
  const FileHeader* header_ = nullptr;
  std::vector<SectionEntry> table_;
  uint64_t packedBytes_ = 0;
  const uint8_t* values_ = nullptr;  // VALU, looked up once
};

// CRC-32C of the 256 header bytes with headerCrc taken as 0: what headerCrc must hold.
uint32_t headerChecksum(const FileHeader& header);

// Checks a header in isolation; `where` prefixes messages (usually the file name).
Status checkHeader(const FileHeader& header, uint64_t fileBytes, const std::string& where);

// Expected payload size of a required section for a given header.
uint64_t expectedSectionBytes(const FileHeader& header, SectionId id, uint64_t metaBytes);
uint32_t expectedElementBytes(const FileHeader& header, SectionId id);
// Entries of VALU and GRAD: one per voxel in version 1, one per volume voxel in version 2.
uint64_t sampleSlots(const FileHeader& header);
// The version 2 sections a header asks for (none for version 1).
std::vector<SectionId> sceneSectionsOf(const FileHeader& header);

// Inline: the validator, the packer's gradient prediction and the writers call these once
// per voxel; a call each cost the prediction a fifth of its time.
inline double VoxLinkFile::storedValue(uint64_t voxel) const {
  const uint8_t* v = values_;
  switch (valueType()) {
    case StoredType::kU8:
      return v[voxel];
    case StoredType::kU16: {
      uint16_t x;
      std::memcpy(&x, v + voxel * 2, 2);
      return x;
    }
    case StoredType::kF16: {
      uint16_t x;
      std::memcpy(&x, v + voxel * 2, 2);
      return halfToFloat(x);
    }
    case StoredType::kF32: {
      float x;
      std::memcpy(&x, v + voxel * 4, 4);
      return x;
    }
  }
  return 0;
}

inline double VoxLinkFile::value(uint64_t voxel) const {
  return storedValue(voxel) * header_->valueScale + header_->valueOffset;
}

}  // namespace voxlink::format
