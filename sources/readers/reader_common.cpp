#include "sources/readers/reader_common.h"

#include <cmath>
#include <fstream>

namespace voxlink::convert {

Status checkDims(const std::array<uint64_t, 3>& dims, const std::string& file,
                 std::string_view field) {
  uint64_t voxels = 1;
  for (int a = 0; a < 3; ++a) {
    if (dims[a] == 0)
      return makeError(ErrorCode::kCorrupt, file, ": header field '", field, "': axis ", a,
                       " has size 0");
    if (dims[a] > UINT32_MAX || voxels > kMaxVoxels / dims[a])
      return makeError(ErrorCode::kTooLarge, file, ": header field '", field, "': ", dims[0], "x",
                       dims[1], "x", dims[2], " is more than ", kMaxVoxels, " voxels");
    voxels *= dims[a];
  }
  return Status::ok();
}

Status checkSpacing(const std::array<double, 3>& spacing, const std::string& file,
                    std::string_view field) {
  for (int a = 0; a < 3; ++a)
    if (!std::isfinite(spacing[a]) || spacing[a] <= 0)
      return makeError(ErrorCode::kCorrupt, file, ": header field '", field, "': spacing of axis ",
                       a, " is ", spacing[a], ", expected a positive number");
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
  std::ifstream in(path, std::ios::binary);
  if (!in) return false;
  std::string head(magic.size(), '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  return in.gcount() == static_cast<std::streamsize>(magic.size()) && head == magic;
}

}  // namespace voxlink::convert
