// SPDX-License-Identifier: BSD-3-Clause
#include "render/image.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>

#include "imageio/image_io.h"

namespace voxlink::render {
namespace {

std::string lowerExtension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  return ext;
}

bool finitePixel(const float* p) {
  return std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]) && std::isfinite(p[3]);
}

}  // namespace

double srgbEncode(double x) {
  x = std::clamp(x, 0.0, 1.0);
  return x <= 0.0031308 ? 12.92 * x : 1.055 * std::pow(x, 1.0 / 2.4) - 0.055;
}

double srgbDecode(double x) {
  return x <= 0.04045 ? x / 12.92 : std::pow((x + 0.055) / 1.055, 2.4);
}

Result<ImageError> compareImages(const Image& a, const Image& b, double threshold) {
  if (a.width != b.width || a.height != b.height)
    return makeError(ErrorCode::kSizeMismatch, "compareImages: sizes differ: ", a.width, "x",
                     a.height, " vs ", b.width, "x", b.height);
  ImageError e;
  double sum = 0;
  const size_t pixels = size_t{a.width} * a.height;
  for (size_t i = 0; i < pixels; ++i) {
    const float* pa = &a.rgba[i * 4];
    const float* pb = &b.rgba[i * 4];
    if (!finitePixel(pa) || !finitePixel(pb)) {
      ++e.nonFinite;
      continue;
    }
    double worst = 0;
    for (int c = 0; c < 3; ++c) {
      const double d = std::clamp<double>(pa[c], 0, 1) - std::clamp<double>(pb[c], 0, 1);
      sum += d * d;
      worst = std::max(worst, std::abs(d));
    }
    e.maxError = std::max(e.maxError, worst);
    if (worst > threshold) ++e.pixelsOver;
  }
  const double mse = pixels ? sum / (3.0 * pixels) : 0.0;
  e.rmse = std::sqrt(mse);
  e.psnr = mse > 0 ? 10.0 * std::log10(1.0 / mse) : std::numeric_limits<double>::infinity();
  return e;
}

Status writeImage(const Image& image, const std::string& path) {
  if (image.width == 0 || image.height == 0)
    return makeError(ErrorCode::kInvalidArgument, path, ": cannot write an empty image");
  const int w = int(image.width), h = int(image.height);
  // EXR keeps the coverage in alpha; 8-bit files are opaque (the background is composited).
  if (lowerExtension(path) == ".exr")
    return imageio::write(path, w, h, 4, ScalarType::kF32, image.rgba.data(), /*halfFloat=*/true,
                          "Linear");
  std::vector<uint8_t> bytes(size_t{image.width} * image.height * 3);
  for (size_t i = 0; i < bytes.size(); ++i) {
    const double v = srgbEncode(image.rgba[i / 3 * 4 + i % 3]);
    bytes[i] = static_cast<uint8_t>(std::lround(std::isfinite(v) ? v * 255.0 : 0.0));
  }
  return imageio::write(path, w, h, 3, ScalarType::kU8, bytes.data(), /*halfFloat=*/false, "sRGB");
}

}  // namespace voxlink::render
