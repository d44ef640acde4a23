// SPDX-License-Identifier: BSD-3-Clause
#include "sources/readers/raw_reader.h"

#include <cstring>

#include "base/mapped_file.h"
#include "sources/readers/detail/byte_order.h"
#include "sources/readers/reader_common.h"

namespace voxlink::sources {
namespace {

class RawSource final : public VolumeSource {
 public:
  RawSource(VolumeInfo info, base::MappedFile file, uint64_t offset, bool swap)
      : file_(std::move(file)), offset_(offset), swap_(swap) {
    info_ = std::move(info);
  }

  bool randomAccess() const override { return true; }

  Status read(uint32_t z0, uint32_t count, void* dst) override {
    VOXLINK_RETURN_IF_ERROR(checkSliceRange(z0, count));
    const uint64_t bytes = uint64_t{count} * info_.sliceBytes();
    const uint64_t begin = offset_ + uint64_t{z0} * info_.sliceBytes();
    std::memcpy(dst, file_.data() + begin, bytes);
    if (swap_) swapBytesInPlace(dst, count * info_.sliceVoxels(), scalarSize(info_.type));
    file_.release(begin, bytes);
    return Status::ok();
  }

  const void* map(uint32_t z0, uint32_t count) override {
    if (swap_ || uint64_t{z0} + count > info_.dims[2]) return nullptr;
    const uint64_t begin = offset_ + uint64_t{z0} * info_.sliceBytes();
    if (begin % scalarSize(info_.type) != 0) return nullptr;  // unaligned elements
    file_.willNeed(begin, uint64_t{count} * info_.sliceBytes());
    return file_.data() + begin;
  }

  void unmap(uint32_t z0, uint32_t count) override {
    file_.release(offset_ + uint64_t{z0} * info_.sliceBytes(),
                  uint64_t{count} * info_.sliceBytes());
  }

 private:
  base::MappedFile file_;
  uint64_t offset_;
  bool swap_;
};

}  // namespace

Result<std::unique_ptr<VolumeSource>> openRawData(const std::string& dataPath, VolumeInfo info,
                                                  Endian endian, uint64_t headerBytes,
                                                  bool exactSize) {
  VOXLINK_RETURN_IF_ERROR(checkVolumeShape(info, "dims"));
  VOXLINK_ASSIGN_OR_RETURN(base::MappedFile file, base::MappedFile::open(dataPath));
  const uint64_t needed = info.voxelCount() * scalarSize(info.type);  // bounded by checkVolumeShape
  const uint64_t available = file.size() > headerBytes ? file.size() - headerBytes : 0;
  const std::string shape =
      cat(info.dims[0], "x", info.dims[1], "x", info.dims[2], " ", scalarName(info.type));
  if (available < needed)
    return makeError(ErrorCode::kTruncated, dataPath, ": data: ", shape, " needs ", needed,
                     " bytes after ", headerBytes, " header bytes, the file has only ", available,
                     " (truncated, or wrong dims/type)");
  if (exactSize && available != needed)
    return makeError(ErrorCode::kSizeMismatch, dataPath, ": data: ", shape, " needs ", needed,
                     " bytes but the file has ", available, " after ", headerBytes,
                     " header bytes; check --dims, --type and --header-bytes");
  const bool swap =
      scalarSize(info.type) > 1 && ((endian == Endian::kLittle) != kHostIsLittleEndian);
  return std::unique_ptr<VolumeSource>(
      new RawSource(std::move(info), std::move(file), headerBytes, swap));
}

Result<std::unique_ptr<VolumeSource>> openRaw(const std::string& path, const OpenOptions& options) {
  if (!options.dims || !options.type)
    return makeError(
        ErrorCode::kInvalidArgument, path,
        ": a raw file needs --dims X,Y,Z and --type (u8, i8, u16, i16, u32, i32, f32, f64)");
  VolumeInfo info;
  info.dims = *options.dims;
  info.path = path;
  if (Status s = checkVolumeShape(info, "--dims"); !s)
    return Error{ErrorCode::kInvalidArgument, s.message()};
  info.type = *options.type;
  if (options.spacing) info.spacing = *options.spacing;
  info.path = path;
  info.format = "raw";
  return openRawData(path, std::move(info), options.endian, options.headerBytes, true);
}

}  // namespace voxlink::sources
