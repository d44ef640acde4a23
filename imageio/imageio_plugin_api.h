// SPDX-License-Identifier: BSD-3-Clause
// The function table of the image plugin, in the style of sources/plugin_api.h (one extern "C"
// entry returning a table of plain functions).
#pragma once

#include <string>

#include "base/error.h"
#include "format/scalar_type.h"
#include "imageio/image_io.h"

namespace voxlink::imageio {

// libvoxlink_imageio_oiio.so: 2-D image files with OpenImageIO (imageio/image_io.h says what
// each call does; write() here writes `path` itself, the client handles the temporary name).
struct ImageIoPluginApi {
  Result<imageio::ImageSpec> (*probe)(const std::string& path, int subimage);
  Result<int> (*subimageCount)(const std::string& path);
  Status (*read)(const std::string& path, int subimage, int channels, ScalarType as, void* dst);
  Status (*write)(const std::string& path, int width, int height, int channels, ScalarType from,
                  const void* pixels, bool halfFloat, const char* colorSpace);
};
inline constexpr const char* kImageIoPlugin = "libvoxlink_imageio_oiio.so";
inline constexpr const char* kImageIoPluginEntry = "voxlink_imageio_plugin";

}  // namespace voxlink::imageio

// The plugin's one exported symbol (kImageIoPluginEntry), defined in plugins/oiio_plugin.cpp.
extern "C" __attribute__((visibility("default"))) const voxlink::imageio::ImageIoPluginApi*
voxlink_imageio_plugin();
