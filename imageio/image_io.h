// SPDX-License-Identifier: BSD-3-Clause
// 2-D image files (TIFF/PNG/EXR/...) for slice stacks and screenshots, through OpenImageIO.
//
// OpenImageIO drags about 250 shared libraries into a process (OpenCV, ffmpeg, libheif, ...),
// which costs ~0.3 s at every start of `voxlink`. So it lives in a plugin,
// libvoxlink_imageio_oiio.so, loaded the first time a function here is called; commands that
// touch no image file never pay for it.
#pragma once

#include <string>

#include "base/error.h"
#include "format/scalar_type.h"

namespace voxlink::imageio {

struct ImageSpec {
  int width = 0, height = 0, depth = 1, channels = 0;
  // The pixel type as a ScalarType; half floats are reported as f32 with halfFloat set.
  ScalarType type = ScalarType::kU8;
  bool halfFloat = false;
  bool supportedType = true;  // false for pixel types without a ScalarType (formatName says which)
  std::string formatName;     // OpenImageIO's name of the pixel type, e.g. "uint8"
};

// Spec of page `subimage` of an image file.
Result<ImageSpec> probe(const std::string& path, int subimage = 0);
// Number of pages (subimages) of an image file.
Result<int> subimageCount(const std::string& path);
// Reads the first `channels` channels of page `subimage`, interleaved, converted to `as`.
Status read(const std::string& path, int subimage, int channels, ScalarType as, void* dst);
// Writes `channels` interleaved channels of `pixels` (u8 or f32 as `from`); the file stores
// 8-bit pixels, or half floats when `halfFloat`. `colorSpace` is recorded ("sRGB", "Linear").
Status write(const std::string& path, int width, int height, int channels, ScalarType from,
             const void* pixels, bool halfFloat, const char* colorSpace);

}  // namespace voxlink::imageio
