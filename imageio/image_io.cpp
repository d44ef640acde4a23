#include "imageio/image_io.h"

#include <unistd.h>

#include <atomic>
#include <filesystem>

#include "plugins/imageio_plugin_api.h"
#include "plugins/plugin_loader.h"

namespace voxlink::imageio {
namespace {

using Plugin = plugins::ImageIoPluginApi;

Result<const Plugin*> plugin() {
  return plugins::pluginApi<Plugin>(plugins::kImageIoPlugin, plugins::kImageIoPluginEntry);
}

}  // namespace

Result<ImageSpec> probe(const std::string& path, int subimage) {
  VOXLINK_ASSIGN_OR_RETURN(const Plugin* p, plugin());
  return p->probe(path, subimage);
}

Result<int> subimageCount(const std::string& path) {
  VOXLINK_ASSIGN_OR_RETURN(const Plugin* p, plugin());
  return p->subimageCount(path);
}

Status read(const std::string& path, int subimage, int channels, ScalarType as, void* dst) {
  VOXLINK_ASSIGN_OR_RETURN(const Plugin* p, plugin());
  return p->read(path, subimage, channels, as, dst);
}

Status write(const std::string& path, int width, int height, int channels, ScalarType from,
             const void* pixels, bool halfFloat, const char* colorSpace) {
  VOXLINK_ASSIGN_OR_RETURN(const Plugin* p, plugin());
  // Written beside the destination under a temporary name that keeps the extension (it picks
  // the format), then renamed: a failed write never leaves a partial image at `path`.
  static std::atomic<unsigned> serial{0};
  const std::filesystem::path target(path);
  const std::filesystem::path temp =
      target.parent_path() / cat(".", target.stem().string(), ".tmp-", getpid(), "-", serial++,
                                 target.extension().string());
  const std::string tempPath = temp.string();
  Status written = p->write(tempPath, width, height, channels, from, pixels, halfFloat, colorSpace);
  std::error_code ec;
  if (!written) {
    std::filesystem::remove(temp, ec);
    std::string message = written.message();
    for (size_t at; (at = message.find(tempPath)) != std::string::npos;)
      message.replace(at, tempPath.size(), path);
    return makeError(written.code(), message);
  }
  std::filesystem::rename(temp, target, ec);
  if (ec) {
    std::filesystem::remove(temp, ec);
    return makeError(ErrorCode::kIo, path,
                     ": cannot move the finished image into place: ", ec.message());
  }
  return Status::ok();
}

}  // namespace voxlink::imageio
