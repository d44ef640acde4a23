// The interface the OpenImageIO plugin implements (same compiler and standard library on both
// sides: the plugin is built with the project). See image_io.h for the meaning of each call.
#pragma once

#include "imageio/image_io.h"

namespace voxlink::imageio {

class Backend {
 public:
  virtual ~Backend() = default;
  virtual Result<ImageSpec> probe(const std::string& path, int subimage) = 0;
  virtual Result<int> subimageCount(const std::string& path) = 0;
  virtual Status read(const std::string& path, int subimage, int channels, ScalarType as, void* dst) = 0;
  virtual Status write(const std::string& path, int width, int height, int channels, ScalarType from,
                       const void* pixels, bool halfFloat, const char* colorSpace) = 0;
};

}  // namespace voxlink::imageio

// The plugin's one exported symbol.
extern "C" voxlink::imageio::Backend* voxlink_imageio_backend();
