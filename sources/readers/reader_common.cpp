// SPDX-License-Identifier: BSD-3-Clause
#include "sources/readers/reader_common.h"

#include <cmath>
#include <fstream>

#include "base/regular_file.h"

namespace voxlink::sources {

Status checkDims(const std::array<uint64_t, 3>& dims, const std::string& file,
                 std::string_view field) {
  const char* kind = field.starts_with("--") ? "option" : "header field";
  for (int a = 0; a < 3; ++a) {
    if (dims[a] == 0)
      return makeError(ErrorCode::kCorrupt, file, ": ", kind, " '", field, "': axis ", a,
                       " has size 0");
    if (dims[a] > limits::kMaxAxis)
      return makeError(ErrorCode::kTooLarge, file, ": ", kind, " '", field, "': axis ", a,
                       " has size ", dims[a], ", more than ", limits::kMaxAxis);
  }
  const auto voxels = checkedProduct({dims[0], dims[1], dims[2]});
  if (!voxels || *voxels > limits::kMaxVoxels)
    return makeError(ErrorCode::kTooLarge, file, ": ", kind, " '", field, "': ", dims[0], "x",
                     dims[1], "x", dims[2], " is more than ", limits::kMaxVoxels, " voxels");
  return Status::ok();
}

Status checkVolumeShape(const VolumeInfo& info, std::string_view field) {
  return checkDims({info.dims[0], info.dims[1], info.dims[2]}, info.path, field);
}

Status checkSpacing(const std::array<double, 3>& spacing, const std::string& file,
                    std::string_view field) {
  for (int a = 0; a < 3; ++a)
    if (!std::isfinite(spacing[a]) || spacing[a] <= 0)
      return makeError(ErrorCode::kCorrupt, file, ": header field '", field, "': spacing of axis ",
                       a, " is ", spacing[a], ", expected a positive number");
  return Status::ok();
}

Status checkOrigin(const std::array<double, 3>& origin, const std::string& file,
                   std::string_view field) {
  for (int a = 0; a < 3; ++a)
    if (!std::isfinite(origin[a]))
      return makeError(ErrorCode::kCorrupt, file, ": header field '", field, "': origin of axis ",
                       a, " is ", origin[a], ", expected a finite number");
  return Status::ok();
}

Status applyOpenOptions(VolumeInfo& info, const OpenOptions& options) {
  if (options.dims && *options.dims != info.dims)
    return makeError(ErrorCode::kInvalidArgument, info.path, ": --dims ", (*options.dims)[0], ",",
                     (*options.dims)[1], ",", (*options.dims)[2], " disagree with the header's ",
                     info.dims[0], "x", info.dims[1], "x", info.dims[2]);
  if (options.type && *options.type != info.type)
    return makeError(ErrorCode::kInvalidArgument, info.path, ": --type ", scalarName(*options.type),
                     " disagrees with the header's ", scalarName(info.type));
  if (options.spacing) {
    info.notes.push_back(cat("spacing ", info.spacing[0], " ", info.spacing[1], " ",
                             info.spacing[2], " from the file replaced by --spacing"));
    info.spacing = *options.spacing;
  }
  return Status::ok();
}

bool fileStartsWith(const std::string& path, std::string_view magic) {
  if (!base::requireRegularFile(path)) return false;  // a FIFO would block the read
  std::ifstream in(path, std::ios::binary);
  if (!in) return false;
  std::string head(magic.size(), '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  return in.gcount() == static_cast<std::streamsize>(magic.size()) && head == magic;
}

}  // namespace voxlink::sources
