// SPDX-License-Identifier: BSD-3-Clause
#include "scene/detail/scene_volume.h"

#include <unistd.h>

#include <atomic>
#include <filesystem>

#include "convert/converter.h"
#include "pack/open_file.h"
#include "sources/volume_source.h"
#include "tf/transfer_function.h"

namespace voxlink::scene {

Result<format::VoxLinkFile> openSceneVolume(
    const SceneObject& object, const SceneGrid& grid,
    const std::function<void(double fraction, const char* stage)>& progress) {
  if (object.thresholds.empty() && object.tfPath.empty()) {
    auto file = pack::openFile(object.path);
    if (!file && file.code() == ErrorCode::kNotAVoxLinkFile)
      return makeError(ErrorCode::kInvalidArgument, object.path,
                       ": not a .vxl; a dense volume in a scene needs \"threshold\" or \"tf\"");
    return file;
  }
  convert::ConvertOptions options;
  options.brickSize = grid.brickSize;
  options.axis = grid.axis;
  if (!object.tfPath.empty()) {
    VOXLINK_ASSIGN_OR_RETURN(tf::TransferFunction tf, tf::loadTransferFunction(object.tfPath));
    options.classification = convert::tfClassification(tf);
  } else {
    VOXLINK_ASSIGN_OR_RETURN(options.classification,
                             convert::thresholdClassification(object.thresholds));
  }
  options.progress = progress;
  VOXLINK_ASSIGN_OR_RETURN(auto source, sources::openVolume(object.path, options.sourceOptions));
  static std::atomic<unsigned> counter{0};
  const std::filesystem::path temp =
      std::filesystem::temp_directory_path() /
      cat("voxlink-scene-volume-", ::getpid(), "-", counter++, ".vxl");
  auto converted = convert::convertVolume(*source, options, temp.string());
  if (!converted) return converted.error();
  auto file = pack::openFile(temp.string());
  std::error_code ignored;
  std::filesystem::remove(temp, ignored);  // an open file stays readable
  return file;
}

}  // namespace voxlink::scene
