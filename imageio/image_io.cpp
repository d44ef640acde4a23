#include "imageio/image_io.h"

#include <dlfcn.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <mutex>
#include <vector>

#include "imageio/backend.h"

namespace voxlink::imageio {
namespace {

constexpr const char* kPluginName = "libvoxlink_imageio_oiio.so";

std::vector<std::string> candidates() {
  std::vector<std::string> paths;
  if (const char* env = std::getenv("VOXLINK_IMAGEIO_PLUGIN")) paths.emplace_back(env);
  std::error_code ec;
  const auto exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    const auto dir = exe.parent_path();
    paths.push_back((dir / kPluginName).string());
    paths.push_back((dir / ".." / "lib" / "voxlink" / kPluginName).lexically_normal().string());
  }
#ifdef VOXLINK_IMAGEIO_PLUGIN_BUILD_PATH
  paths.emplace_back(VOXLINK_IMAGEIO_PLUGIN_BUILD_PATH);  // the build tree, for tests and tools
#endif
#ifdef VOXLINK_IMAGEIO_PLUGIN_INSTALL_PATH
  paths.emplace_back(VOXLINK_IMAGEIO_PLUGIN_INSTALL_PATH);
#endif
  return paths;
}

struct Loaded {
  Backend* backend = nullptr;
  std::string path;
  std::string error;
};

const Loaded& loaded() {
  static Loaded result;
  static std::once_flag once;
  std::call_once(once, [] {
    std::string tried;
    for (const std::string& path : candidates()) {
      std::error_code ec;
      if (!std::filesystem::exists(path, ec)) {
        tried += (tried.empty() ? "" : ", ") + path;
        continue;
      }
      void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
      if (!handle) {
        result.error = cat(path, ": cannot load the image plugin: ", dlerror());
        return;
      }
      auto create = reinterpret_cast<Backend* (*)()>(dlsym(handle, "voxlink_imageio_backend"));
      if (!create) {
        result.error = cat(path, ": not a VoxLink image plugin (no voxlink_imageio_backend)");
        return;
      }
      result.backend = create();
      result.path = path;
      return;  // the handle stays open for the life of the process
    }
    result.error = cat("image file support needs ", kPluginName, ", built with VoxLink; not found in: ", tried,
                       " (set VOXLINK_IMAGEIO_PLUGIN to its path)");
  });
  return result;
}

Result<Backend*> backend() {
  const Loaded& l = loaded();
  if (!l.backend) return makeError(ErrorCode::kUnsupported, l.error);
  return l.backend;
}

}  // namespace

Result<std::string> pluginPath() {
  VOXLINK_RETURN_IF_ERROR(backend().status());
  return loaded().path;
}

Result<ImageSpec> probe(const std::string& path, int subimage) {
  VOXLINK_ASSIGN_OR_RETURN(Backend * b, backend());
  return b->probe(path, subimage);
}

Result<int> subimageCount(const std::string& path) {
  VOXLINK_ASSIGN_OR_RETURN(Backend * b, backend());
  return b->subimageCount(path);
}

Status read(const std::string& path, int subimage, int channels, ScalarType as, void* dst) {
  VOXLINK_ASSIGN_OR_RETURN(Backend * b, backend());
  return b->read(path, subimage, channels, as, dst);
}

Status write(const std::string& path, int width, int height, int channels, ScalarType from,
             const void* pixels, bool halfFloat, const char* colorSpace) {
  VOXLINK_ASSIGN_OR_RETURN(Backend * b, backend());
  return b->write(path, width, height, channels, from, pixels, halfFloat, colorSpace);
}

}  // namespace voxlink::imageio
