// SPDX-License-Identifier: BSD-3-Clause
#include "imageio/image_io.h"

#include <unistd.h>

#include <filesystem>
#include <vector>

#include "base/output_file.h"
#include "base/plugin_loader.h"
#include "base/stderr_capture.h"
#include "imageio/imageio_plugin_api.h"

namespace voxlink::imageio {
namespace {

using Plugin = imageio::ImageIoPluginApi;

Result<const Plugin*> plugin() {
  return base::pluginApi<Plugin>(imageio::kImageIoPlugin, imageio::kImageIoPluginEntry);
}

}  // namespace

// libpng (under OpenImageIO) prints warnings such as "libpng warning: iCCP: known incorrect
// sRGB profile" to stderr: captured, so our messages stay one line; a failure quotes it.
template <class R>
R quoting(const base::StderrCapture& capture, R result) {
  if (result) return result;
  const std::string said = capture.firstLine();
  if (said.empty()) return result;
  return Error{result.code(), cat(result.message(), " (", said, ")")};
}

Result<ImageSpec> probe(const std::string& path, int subimage) {
  VOXLINK_ASSIGN_OR_RETURN(const Plugin* p, plugin());
  base::StderrCapture capture;
  return quoting(capture, p->probe(path, subimage));
}

Result<int> subimageCount(const std::string& path) {
  VOXLINK_ASSIGN_OR_RETURN(const Plugin* p, plugin());
  base::StderrCapture capture;
  return quoting(capture, p->subimageCount(path));
}

Status read(const std::string& path, int subimage, int channels, ScalarType as, void* dst) {
  VOXLINK_ASSIGN_OR_RETURN(const Plugin* p, plugin());
  base::StderrCapture capture;
  return quoting(capture, p->read(path, subimage, channels, as, dst));
}

Status write(const std::string& path, int width, int height, int channels, ScalarType from,
             const void* pixels, bool halfFloat, const char* colorSpace) {
  VOXLINK_ASSIGN_OR_RETURN(const Plugin* p, plugin());
  // Written beside the destination under a unique temporary name (O_EXCL) that keeps the
  // extension (it picks the format), then renamed: a failed write never leaves a partial image
  // at `path`. The plugin checks every write and the close (a full disk fails there).
  const std::string extension = std::filesystem::path(path).extension().string();
  VOXLINK_ASSIGN_OR_RETURN(base::TempFile temp, base::createTempBeside(path, extension));
  ::close(temp.fd);  // the backend opens the file by name
  const std::string tempPath = temp.path;
  base::StderrCapture capture;
  Status written = p->write(tempPath, width, height, channels, from, pixels, halfFloat, colorSpace);
  if (written) {
    // Image libraries do not all report a short write (a full disk left truncated PNGs behind
    // with success): the file must read back whole before it replaces anything.
    std::vector<float> back(size_t(width) * size_t(height) * size_t(channels));
    if (Status s = p->read(tempPath, 0, channels, ScalarType::kF32, back.data()); !s)
      written = makeError(ErrorCode::kIo, path,
                          ": write failed: the written image does not read "
                          "back (disk full?)");
  }
  if (!written) {
    base::discardTemp(tempPath);
    std::string message = written.message();
    for (size_t at; (at = message.find(tempPath)) != std::string::npos;)
      message.replace(at, tempPath.size(), path);
    return makeError(written.code(), message);
  }
  return base::commitTemp(tempPath, path);
}

}  // namespace voxlink::imageio
