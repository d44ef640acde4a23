// SPDX-License-Identifier: BSD-3-Clause
// Float RGBA images (linear colour, row 0 at the top) as both renderers produce them, the error
// measures between two of them, and writing them through OpenImageIO (imageio/, a plugin).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "base/error.h"

namespace voxlink::render {

struct Image {
  uint32_t width = 0;
  uint32_t height = 0;
  std::vector<float> rgba;  // width * height * 4

  Image() = default;
  Image(uint32_t w, uint32_t h) : width(w), height(h), rgba(size_t{w} * h * 4, 0.0f) {}
  float* pixel(uint32_t x, uint32_t y) { return &rgba[(size_t{y} * width + x) * 4]; }
  const float* pixel(uint32_t x, uint32_t y) const { return &rgba[(size_t{y} * width + x) * 4]; }
};

struct ImageError {
  double psnr = 0;  // dB over RGB clamped to [0, 1]; +inf when identical
  double rmse = 0;
  double maxError = 0;      // largest |a - b| over RGB channels
  uint64_t nonFinite = 0;   // pixels of either image with a NaN or infinite channel
  uint64_t pixelsOver = 0;  // pixels whose max channel error exceeds the threshold given
};

// Fails when the sizes differ. `threshold` counts pixels with a larger channel error.
Result<ImageError> compareImages(const Image& a, const Image& b, double threshold = 1.0 / 255);

// Writes PNG (8-bit sRGB-encoded RGB, opaque) or EXR (half-float linear RGBA, alpha = coverage)
// by the file's extension; other extensions OpenImageIO knows get 8-bit sRGB RGB.
Status writeImage(const Image& image, const std::string& path);

double srgbEncode(double linear);
double srgbDecode(double encoded);

}  // namespace voxlink::render
