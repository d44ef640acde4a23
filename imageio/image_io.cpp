#include "imageio/image_io.h"

#include "imageio/backend.h"
#include "plugins/plugin_loader.h"

namespace voxlink::imageio {
namespace {

Result<Backend*> backend() {
  using Create = Backend* (*)();
  VOXLINK_ASSIGN_OR_RETURN(void* entry, plugins::pluginEntry("libvoxlink_imageio_oiio.so", "voxlink_imageio_backend"));
  static Backend* instance = reinterpret_cast<Create>(entry)();
  return instance;
}

}  // namespace

Result<std::string> pluginPath() {
  VOXLINK_RETURN_IF_ERROR(backend().status());
  return plugins::pluginLocation("libvoxlink_imageio_oiio.so");
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
