// SPDX-License-Identifier: BSD-3-Clause
#include "sources/volume_source.h"

#include <algorithm>
#include <filesystem>

#include "base/regular_file.h"
#include "sources/readers/detail/reader_registry.h"
#include "sources/readers/raw_reader.h"
#include "sources/readers/reader_common.h"

namespace voxlink::sources {

Status VolumeSource::checkSliceRange(uint32_t z0, uint32_t count) const {
  if (uint64_t{z0} + count > info_.dims[2])
    return makeError(ErrorCode::kInvalidArgument, info_.path, ": slices [", z0, ", ",
                     uint64_t{z0} + count, ") beyond z size ", info_.dims[2]);
  return Status::ok();
}

Status VolumeSource::readActive(uint32_t z0, uint32_t count, uint8_t* dst) {
  VOXLINK_RETURN_IF_ERROR(checkSliceRange(z0, count));
  std::fill_n(dst, info_.sliceVoxels() * count, uint8_t{1});
  return Status::ok();
}

void VolumeSource::recordFileRead(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) return;
  if (std::find(info_.files.begin(), info_.files.end(), path) == info_.files.end())
    info_.files.push_back(path);
}

Result<std::vector<uint8_t>> readAll(VolumeSource& source) {
  const VolumeInfo& info = source.info();
  const uint64_t bytes = info.voxelCount() * scalarSize(info.type);
  std::vector<uint8_t> data;
  try {
    data.resize(bytes);
  } catch (const std::bad_alloc&) {
    return makeError(ErrorCode::kTooLarge, info.path, ": ", bytes, " bytes do not fit in memory");
  }
  VOXLINK_RETURN_IF_ERROR(source.rewind());
  VOXLINK_RETURN_IF_ERROR(source.read(0, info.dims[2], data.data()));
  return data;
}

std::vector<std::string> readerNames() {
  std::vector<std::string> names;
  for (const ReaderEntry& r : readerRegistry()) names.push_back(r.name);
  return names;
}

namespace {

// Every reader checks its header before allocating; this repeats the shape limits on whatever a
// reader returns, so no command (convert, stats, ...) sees a volume beyond them.
Result<std::unique_ptr<VolumeSource>> checked(const std::string& path,
                                              Result<std::unique_ptr<VolumeSource>> source) {
  if (!source) return source;
  (*source)->recordFileRead(path);  // the header, or the only file; a folder is no file
  const VolumeInfo& info = (*source)->info();
  VOXLINK_RETURN_IF_ERROR(checkVolumeShape(info, "dims"));
  // Readers name the field when they check; this catches any reader that does not.
  VOXLINK_RETURN_IF_ERROR(checkSpacing(info.spacing, info.path, "spacing"));
  VOXLINK_RETURN_IF_ERROR(checkOrigin(info.origin, info.path, "origin"));
  return source;
}

// --variable names one of several variables; a format with a single unnamed one would
// silently read that one instead of the variable asked for.
Status checkVariableTaken(const std::string& reader, const std::string& path,
                          const OpenOptions& options) {
  if (options.variable.empty()) return Status::ok();
  return makeError(ErrorCode::kInvalidArgument, path, ": --variable '", options.variable, "': the ",
                   reader,
                   " reader has no named variables (--variable picks a GSLIB/GEO-EAS column or "
                   "a .vti point data array)");
}

Result<std::unique_ptr<VolumeSource>> openWith(const ReaderEntry& reader, const std::string& path,
                                               const OpenOptions& options) {
  if (!reader.namedVariables)
    VOXLINK_RETURN_IF_ERROR(checkVariableTaken(reader.name, path, options));
  return reader.open(path, options);
}

Result<std::unique_ptr<VolumeSource>> openWithReader(const std::string& path,
                                                     const OpenOptions& options) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec))
    return makeError(ErrorCode::kIo, path, ": no such file or directory");
  // Folders hold DICOM series and image stacks; anything else must be a regular file (a FIFO
  // or device would block the readers' probes forever).
  if (!std::filesystem::is_directory(path, ec))
    VOXLINK_RETURN_IF_ERROR(base::requireRegularFile(path, "volume"));
  const auto& registry = readerRegistry();
  if (!options.format.empty()) {
    for (const ReaderEntry& r : registry)
      if (r.name == options.format) return openWith(r, path, options);
    std::string known;
    for (const ReaderEntry& r : registry) known += (known.empty() ? "" : ", ") + r.name;
    return makeError(ErrorCode::kInvalidArgument, path, ": --format ", options.format,
                     " is not one of: ", known);
  }
  for (const ReaderEntry& r : registry)
    if (r.matches(path)) return openWith(r, path, options);
  // A file no reader claims is raw when dims and type were given.
  if (options.dims && options.type) {
    VOXLINK_RETURN_IF_ERROR(checkVariableTaken("raw", path, options));
    return openRaw(path, options);
  }
  return makeError(ErrorCode::kUnsupported, path,
                   ": unknown volume format; give --format, or --dims and --type for a raw file");
}

}  // namespace

Result<std::unique_ptr<VolumeSource>> openVolume(const std::string& path,
                                                 const OpenOptions& options) {
  return checked(path, openWithReader(path, options));
}

}  // namespace voxlink::sources
