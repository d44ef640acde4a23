// SPDX-License-Identifier: BSD-3-Clause
#include "format/file_writer.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <bit>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <optional>

#include "base/check.h"
#include "base/crc32c.h"
#include "base/mapped_file.h"
#include "base/output_file.h"
#include "format/voxlink_file.h"

namespace voxlink::format {
namespace {

uint64_t ceilDiv(uint64_t a, uint64_t b) { return (a + b - 1) / b; }

// A writer's header came from makeHeader() (a scene's then says version 2): the fixed fields it
// sets, and a brick grid that matches the dims (planSections sizes every section from these).
void checkMadeByMakeHeader(const FileHeader& h) {
  VOXLINK_CHECK(std::memcmp(h.magic, kMagic, sizeof(kMagic)) == 0, "header not from makeHeader()");
  VOXLINK_CHECK(h.versionMajor == kVersionMajor || h.versionMajor == kVersionMajorScene,
                "header not from makeHeader() or a scene's");
  VOXLINK_CHECK_EQ(h.headerBytes, sizeof(FileHeader));
  VOXLINK_CHECK_GT(h.brickSize, 0u);
  for (int a = 0; a < 3; ++a) VOXLINK_CHECK_EQ(h.brickGrid[a], ceilDiv(h.dims[a], h.brickSize));
}

}  // namespace

Status checkDescription(const VolumeDescription& d) {
  if (!isValidBrickSize(d.brickSize))
    return makeError(ErrorCode::kInvalidArgument, "brick size ", d.brickSize,
                     ": expected 4, 8, 16 or 32");
  for (int a = 0; a < 3; ++a) {
    if (d.dims[a] == 0 || d.dims[a] > kMaxDim)
      return makeError(ErrorCode::kTooLarge, "dims[", a, "] = ", d.dims[a], ": expected 1..",
                       kMaxDim);
    if (!(std::isfinite(d.spacing[a]) && d.spacing[a] > 0))
      return makeError(ErrorCode::kInvalidArgument, "spacing[", a, "] = ", d.spacing[a],
                       ": expected a finite value > 0");
    if (!std::isfinite(d.origin[a]))
      return makeError(ErrorCode::kInvalidArgument, "origin[", a, "] is not finite");
  }
  if (!std::isfinite(d.valueScale) || d.valueScale == 0 || !std::isfinite(d.valueOffset))
    return makeError(ErrorCode::kInvalidArgument, "value mapping scale ", d.valueScale, " offset ",
                     d.valueOffset, " is not finite and invertible");
  return Status::ok();
}

FileHeader makeHeader(const VolumeDescription& d, uint64_t voxelCount, uint64_t occupiedBricks) {
  FileHeader h{};
  std::memcpy(h.magic, kMagic, sizeof(kMagic));
  h.versionMajor = kVersionMajor;
  h.versionMinor = kVersionMinor;
  h.byteOrderMark = kByteOrderMark;
  h.headerBytes = sizeof(FileHeader);
  h.brickSize = d.brickSize;
  for (int a = 0; a < 3; ++a) {
    h.dims[a] = d.dims[a];
    h.brickGrid[a] = static_cast<uint32_t>(ceilDiv(d.dims[a], d.brickSize));
    h.spacing[a] = d.spacing[a];
    h.origin[a] = d.origin[a];
  }
  h.predominantAxis = static_cast<uint8_t>(d.predominantAxis);
  h.valueType = static_cast<uint8_t>(d.valueType);
  h.gradientCodec = static_cast<uint8_t>(GradientCodec::kPolar16);
  h.sourceType = static_cast<uint8_t>(d.sourceType);
  h.flags = d.flags;
  h.valueScale = d.valueScale;
  h.valueOffset = d.valueOffset;
  h.valueMin = d.valueMin;
  h.valueMax = d.valueMax;
  h.valueMaxAbsError = d.valueMaxAbsError;
  h.valueMaxRelError = d.valueMaxRelError;
  h.valueErrorBound = d.valueErrorBound;
  h.voxelCount = voxelCount;
  h.occupiedBrickCount = occupiedBricks;
  return h;
}

const SectionEntry& SectionLayout::entry(SectionId id) const {
  for (const SectionEntry& e : entries)
    if (e.id == static_cast<uint32_t>(id)) return e;
  return entries.front();  // unreachable for required sections
}

SectionLayout planSections(const FileHeader& header, uint64_t metaBytes) {
  // META goes last so a streaming writer can place every data section before it knows the
  // metadata (which records measured errors).
  SectionLayout layout;
  uint64_t offset = alignUp(sizeof(FileHeader), kSectionAlignment);
  auto place = [&](SectionId id) {
    SectionEntry e{};
    e.id = static_cast<uint32_t>(id);
    e.elementBytes = expectedElementBytes(header, id);
    e.offset = offset;
    e.bytes = expectedSectionBytes(header, id, metaBytes);
    layout.entries.push_back(e);
    offset = alignUp(offset + e.bytes, kSectionAlignment);
  };
  for (SectionId id : kRequiredSections)
    if (id != SectionId::kMeta) place(id);
  for (SectionId id : sceneSectionsOf(header)) place(id);
  place(SectionId::kMeta);
  layout.tableOffset = offset;
  layout.fileBytes = offset + layout.entries.size() * sizeof(SectionEntry);
  return layout;
}

FileWriter::FileWriter(const std::string& path, const FileHeader& header)
    : path_(path), header_(header), layout_(planSections(header, 0)) {
  crcs_.resize(layout_.entries.size());
}

Status FileWriter::takeTemp(const TempFile& temp) {
  fd_ = temp.fd;
  tempPath_ = temp.path;
  unnamedTemp_ = temp.unnamed;
  const uint64_t dataEnd = layout_.entry(SectionId::kMeta).offset;
  if (ftruncate(fd_, static_cast<off_t>(dataEnd)) != 0)
    return makeError(ErrorCode::kIo, path_, ": cannot size output to ", dataEnd,
                     " bytes: ", std::strerror(errno));
  return Status::ok();
}

Result<FileWriter> FileWriter::create(const std::string& path, const FileHeader& header) {
  checkMadeByMakeHeader(header);
  if (header.voxelCount > kMaxVoxels)
    return makeError(ErrorCode::kTooLarge, path, ": ", header.voxelCount,
                     " voxels exceed the format's limit of ", kMaxVoxels,
                     "; classify more strictly or split the volume");
  FileWriter w(path, header);
  // The temporary file sits beside the destination so the final rename stays on one file system;
  // unnamed where possible, so that not even kill -9 leaves a partial file behind.
  VOXLINK_ASSIGN_OR_RETURN(TempFile temp, createUnnamedTempBeside(path));
  VOXLINK_RETURN_IF_ERROR(w.takeTemp(temp));
  return w;
}

Result<FileWriter> FileWriter::createShared(const std::string& path, const FileHeader& header) {
  checkMadeByMakeHeader(header);
  FileWriter w(path, header);
  VOXLINK_ASSIGN_OR_RETURN(TempFile temp, createTempBeside(path));
  VOXLINK_RETURN_IF_ERROR(w.takeTemp(temp));
  return w;
}

Result<FileWriter> FileWriter::attach(const std::string& path, const std::string& tempPath,
                                      const FileHeader& header) {
  checkMadeByMakeHeader(header);
  FileWriter w(path, header);
  w.attached_ = true;
  w.fd_ = ::open(tempPath.c_str(), O_WRONLY | O_CLOEXEC);
  if (w.fd_ < 0)
    return makeError(ErrorCode::kIo, path, ": cannot open the shared temporary ", tempPath, ": ",
                     std::strerror(errno));
  w.tempPath_ = tempPath;
  return w;
}

std::vector<FileWriter::SectionPart> FileWriter::sectionParts() const {
  std::vector<SectionPart> parts;
  for (const RunningCrc& c : crcs_)
    parts.push_back(SectionPart{c.begin, c.covered, c.crc, c.inOrder ? 1u : 0u});
  return parts;
}

Status FileWriter::close() {
  const int fd = std::exchange(fd_, -1);
  tempPath_.clear();
  if (fd >= 0 && ::close(fd) != 0)
    return makeError(ErrorCode::kIo, path_, ": write failed at close: ", std::strerror(errno));
  return Status::ok();
}

FileWriter::FileWriter(FileWriter&& other) noexcept
    : path_(std::move(other.path_)),
      tempPath_(std::move(other.tempPath_)),
      fd_(std::exchange(other.fd_, -1)),
      unnamedTemp_(other.unnamedTemp_),
      attached_(other.attached_),
      header_(other.header_),
      layout_(std::move(other.layout_)),
      crcs_(std::move(other.crcs_)),
      crcMutex_(std::move(other.crcMutex_)) {
  other.tempPath_.clear();
}

FileWriter::~FileWriter() { discard(); }

void FileWriter::discard() {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
  if (!tempPath_.empty() && !unnamedTemp_ && !attached_) discardTemp(tempPath_);
  tempPath_.clear();
}

Status FileWriter::writeRaw(uint64_t fileOffset, const void* data, size_t bytes) {
  const auto* p = static_cast<const uint8_t*>(data);
  while (bytes > 0) {
    const ssize_t n = pwrite(fd_, p, bytes, static_cast<off_t>(fileOffset));
    if (n < 0) {
      if (errno == EINTR) continue;
      return makeError(ErrorCode::kIo, path_, ": write failed: ", std::strerror(errno));
    }
    p += n;
    bytes -= static_cast<size_t>(n);
    fileOffset += static_cast<uint64_t>(n);
  }
  return Status::ok();
}

Status FileWriter::write(SectionId id, uint64_t offset, const void* data, size_t bytes) {
  const SectionEntry& e = layout_.entry(id);
  if (offset + bytes > e.bytes)
    return makeError(ErrorCode::kInvalidArgument, path_, ": section ", sectionName(id),
                     ": write of ", bytes, " bytes at ", offset, " exceeds its ", e.bytes,
                     " bytes");
  VOXLINK_RETURN_IF_ERROR(writeRaw(e.offset + offset, data, bytes));
  std::lock_guard lock(*crcMutex_);
  RunningCrc& c = crcs_[static_cast<size_t>(&e - layout_.entries.data())];
  if (!c.started) c.started = true, c.begin = c.covered = offset;
  if (c.inOrder && offset == c.covered) {
    c.crc = crc32c(data, bytes, c.crc);
    c.covered += bytes;
  } else {
    c.inOrder = false;
  }
  return Status::ok();
}

namespace {

// The checksum of section `index` from the parts of every writer, when they tile it.
std::optional<uint32_t> combinedCrc(const std::vector<FileWriter::SectionPart>& all, size_t index,
                                    size_t sections, uint64_t bytes) {
  std::vector<FileWriter::SectionPart> parts;
  for (size_t at = index; at < all.size(); at += sections)
    if (all[at].end > all[at].begin || !all[at].inOrder) parts.push_back(all[at]);
  std::sort(parts.begin(), parts.end(),
            [](const auto& a, const auto& b) { return a.begin < b.begin; });
  uint32_t crc = 0;
  uint64_t covered = 0;
  for (const FileWriter::SectionPart& p : parts) {
    if (!p.inOrder || p.begin != covered) return std::nullopt;
    crc = crc32cCombine(crc, p.crc, p.end - p.begin);
    covered = p.end;
  }
  // The padding after the data (VALU, GRAD and ROWS to 4 bytes, META) is never written: zeros
  // from ftruncate. Checksummed here, an odd voxel count no longer reads GRAD back from disk.
  constexpr uint8_t kZeros[kSectionAlignment] = {};
  if (bytes > covered && bytes - covered < 4)
    crc = crc32cCombine(crc, crc32c(kZeros, bytes - covered), bytes - covered);
  else if (covered != bytes)
    return std::nullopt;
  return crc;
}

}  // namespace

Status FileWriter::commit(const std::string& metaJson, const std::vector<SectionPart>& otherParts) {
  if (fd_ < 0) return makeError(ErrorCode::kInvalidArgument, path_, ": writer already finished");
  layout_ = planSections(header_, metaJson.size());  // data offsets do not depend on META
  if (ftruncate(fd_, static_cast<off_t>(layout_.fileBytes)) != 0)
    return makeError(ErrorCode::kIo, path_, ": cannot size output to ", layout_.fileBytes,
                     " bytes: ", std::strerror(errno));
  VOXLINK_RETURN_IF_ERROR(write(SectionId::kMeta, 0, metaJson.data(), metaJson.size()));
  {
    // Sections written out of order or with gaps (left as zeros) are read back.
    std::optional<MappedFile> mapped;
    std::vector<SectionPart> parts = sectionParts();
    parts.insert(parts.end(), otherParts.begin(), otherParts.end());
    for (size_t i = 0; i < layout_.entries.size(); ++i) {
      SectionEntry& e = layout_.entries[i];
      if (auto crc = combinedCrc(parts, i, layout_.entries.size(), e.bytes)) {
        e.crc = *crc;
        continue;
      }
      if (!mapped) {
        VOXLINK_ASSIGN_OR_RETURN(MappedFile m, MappedFile::open(tempPath_));
        mapped.emplace(std::move(m));
      }
      e.crc = crc32c(mapped->data() + e.offset, e.bytes);
      mapped->release(e.offset, e.bytes);
    }
  }
  header_.sectionTableOffset = layout_.tableOffset;
  header_.sectionCount = static_cast<uint32_t>(layout_.entries.size());
  header_.headerCrc = headerChecksum(header_);
  VOXLINK_RETURN_IF_ERROR(writeRaw(layout_.tableOffset, layout_.entries.data(),
                                   layout_.entries.size() * sizeof(SectionEntry)));
  VOXLINK_RETURN_IF_ERROR(writeRaw(0, &header_, sizeof(header_)));
  // Local file systems report a full disk at write; network ones may only at close (checked).
  // No fsync: it would cost the conversion seconds on large outputs.
  const TempFile temp{std::exchange(fd_, -1), std::exchange(tempPath_, std::string()),
                      unnamedTemp_};
  return commitTempFile(temp, path_);
}

}  // namespace voxlink::format
