// SPDX-License-Identifier: BSD-3-Clause
// Writing VoxLink files. Output goes to a temporary file beside the destination and is renamed
// into place only by commit(), so a failed or interrupted write never leaves a half-written file.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "base/error.h"
#include "base/output_file.h"
#include "format/layout.h"
#include "format/scalar_type.h"

namespace voxlink::format {

// What the header says about a volume, apart from counts and section bookkeeping.
struct VolumeDescription {
  std::array<uint32_t, 3> dims{0, 0, 0};
  uint32_t brickSize = 8;
  Axis predominantAxis = Axis::kZ;
  StoredType valueType = StoredType::kU8;
  ScalarType sourceType = ScalarType::kU8;
  std::array<double, 3> spacing{1.0, 1.0, 1.0};
  std::array<double, 3> origin{0.0, 0.0, 0.0};
  double valueScale = 1.0;  // source = stored * valueScale + valueOffset
  double valueOffset = 0.0;
  double valueMin = 0.0;  // of the stored voxels, source units
  double valueMax = 0.0;
  double valueMaxAbsError = 0.0;
  double valueMaxRelError = 0.0;
  double valueErrorBound = 0.0;
  uint32_t flags = kFlagGradientsInWorldSpace;
};

Status checkDescription(const VolumeDescription& d);

// Header with every field but the section table and the CRC filled in.
FileHeader makeHeader(const VolumeDescription& d, uint64_t voxelCount, uint64_t occupiedBricks);

struct SectionLayout {
  std::vector<SectionEntry> entries;  // in kRequiredSections order, crc not yet known
  uint64_t tableOffset = 0;
  uint64_t fileBytes = 0;
  const SectionEntry& entry(SectionId id) const;
};

// Places the required sections one after another, each on a kSectionAlignment boundary, META
// last.
SectionLayout planSections(const FileHeader& header, uint64_t metaBytes);

class FileWriter {
 public:
  // `header` must come from makeHeader() (checked: VOXLINK_CHECK). Data sections may be written
  // right away; the META section (placed last) is given to commit().
  static Result<FileWriter> create(const std::string& path, const FileHeader& header);
  // Several processes writing one file (docs/scale.md): one creates it with createShared (a
  // named temporary beside `path`, since the others must open it: tempPath()) and commits it;
  // the others attach() to that temporary, write their parts and close().
  static Result<FileWriter> createShared(const std::string& path, const FileHeader& header);
  static Result<FileWriter> attach(const std::string& path, const std::string& tempPath,
                                   const FileHeader& header);
  FileWriter(FileWriter&& other) noexcept;
  FileWriter& operator=(FileWriter&&) = delete;
  FileWriter(const FileWriter&) = delete;
  ~FileWriter();  // removes the temporary file unless commit() succeeded

  const SectionLayout& layout() const { return layout_; }
  FileHeader& header() { return header_; }  // fields like valueMin may be set before commit()
  const std::string& path() const { return path_; }
  const std::string& tempPath() const { return tempPath_; }

  // What this writer checksummed of one section: bytes [begin, end) written front to back.
  struct SectionPart {
    uint64_t begin = 0, end = 0;
    uint32_t crc = 0;
    uint32_t inOrder = 1;  // 0: written out of order, no usable checksum
  };
  // One per section, in layout().entries order.
  std::vector<SectionPart> sectionParts() const;

  // Writes bytes at `offset` inside a section; thread-safe for disjoint ranges. A section
  // written front to back in order is checksummed on the way; any other order makes commit()
  // read that section back from the file instead.
  Status write(SectionId id, uint64_t offset, const void* data, size_t bytes);
  // Writes META, checksums every section, writes the table and the header, and renames the
  // file into place. `otherParts` are the sectionParts() of the writers attached to this one
  // (each one's list after the other): a section they and this writer cover front to back
  // without gaps gets its checksum combined from theirs; any other is read back.
  Status commit(const std::string& metaJson, const std::vector<SectionPart>& otherParts = {});
  // An attached writer's end: closes the file (checked); the creator commits it.
  Status close();

 private:
  FileWriter(const std::string& path, const FileHeader& header);  // no file yet
  // Writes into `temp` from now on (a discard removes it), sized to the data sections' end.
  Status takeTemp(const TempFile& temp);
  Status writeRaw(uint64_t fileOffset, const void* data, size_t bytes);
  void discard();

  std::string path_;
  std::string tempPath_;
  int fd_ = -1;
  bool unnamedTemp_ = false;  // O_TMPFILE: closing it is all a discard needs
  bool attached_ = false;     // another writer owns the temporary: never removed from here
  FileHeader header_{};
  SectionLayout layout_;
  // The checksum of a section's prefix [0, covered), while writes arrive in order.
  struct RunningCrc {
    uint64_t begin = 0, covered = 0;
    uint32_t crc = 0;
    bool started = false;
    bool inOrder = true;
  };
  std::vector<RunningCrc> crcs_;  // parallel to layout_.entries
  std::unique_ptr<std::mutex> crcMutex_ = std::make_unique<std::mutex>();
};

}  // namespace voxlink::format
