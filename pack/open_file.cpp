// SPDX-License-Identifier: BSD-3-Clause
#include "pack/open_file.h"

#include <memory>
#include <new>
#include <span>
#include <utility>

#include "base/limits.h"
#include "base/mapped_file.h"
#include "format/validator.h"
#include "pack/packed_file.h"

namespace voxlink::pack {

using format::VoxLinkFile;

Result<VoxLinkFile> openFile(const std::string& path) {
  VOXLINK_ASSIGN_OR_RETURN(MappedFile mapped, MappedFile::open(path));
  if (isPackedFile(std::span(mapped.data(), mapped.size())))
    return unpackFile(std::span(mapped.data(), mapped.size()), path, limits::kMaxUnpackedBytes);
  auto holder = std::make_shared<MappedFile>(std::move(mapped));
  const uint8_t* data = holder->data();
  const uint64_t size = holder->size();
  return VoxLinkFile::parseOwned(std::shared_ptr<const void>(holder, holder.get()), data, size,
                                 path);
}

Result<VoxLinkFile> readFile(const std::string& path) {
  VOXLINK_ASSIGN_OR_RETURN(MappedFile mapped, MappedFile::open(path));
  const std::span<const uint8_t> bytes(mapped.data(), mapped.size());
  if (isPackedFile(bytes)) return unpackFile(bytes, path, limits::kMaxUnpackedBytes);
  std::vector<uint8_t> copy;
  try {
    copy.assign(bytes.begin(), bytes.end());
  } catch (const std::bad_alloc&) {
    return makeError(ErrorCode::kTooLarge, path, ": ", bytes.size(), " bytes do not fit in memory");
  }
  return VoxLinkFile::fromBytes(std::move(copy), path);
}

Result<VoxLinkFile> fileFromBytes(std::vector<uint8_t> bytes, const std::string& name) {
  if (isPackedFile(bytes)) return unpackFile(bytes, name, limits::kMaxUnpackedBytes);
  return VoxLinkFile::fromBytes(std::move(bytes), name);
}

Result<VoxLinkFile> openValidatedFile(const std::string& path) {
  VOXLINK_ASSIGN_OR_RETURN(VoxLinkFile file, openFile(path));
  VOXLINK_RETURN_IF_ERROR(format::validateFile(file).status());
  return file;
}

Result<VoxLinkFile> readValidatedFile(const std::string& path) {
  VOXLINK_ASSIGN_OR_RETURN(VoxLinkFile file, readFile(path));
  VOXLINK_RETURN_IF_ERROR(format::validateFile(file).status());
  return file;
}

}  // namespace voxlink::pack
