// The pixel loop the float64 reference renderers share: every primary ray of the frame, rows in
// parallel, each pixel's linear RGBA from trace(ray).
#pragma once

#include <array>

#include "format/parallel_for.h"
#include "viewer/core/camera.h"
#include "viewer/core/image.h"
#include "viewer/core/render_settings.h"

namespace voxlink::viewer {

template <class Trace>
Image renderRows(const Camera& camera, const RenderSettings& settings, const Trace& trace) {
  Image image(settings.width, settings.height);
  format::parallelFor(settings.height, 0, [&](uint64_t row) {
    const auto y = static_cast<uint32_t>(row);
    for (uint32_t x = 0; x < settings.width; ++x) {
      const std::array<double, 4> c =
          trace(camera.primaryRay(x, y, settings.width, settings.height));
      float* p = image.pixel(x, y);
      for (int i = 0; i < 4; ++i) p[i] = static_cast<float>(c[i]);
    }
  });
  return image;
}

}  // namespace voxlink::viewer
