// The pixel loop the float64 reference renderers share: every primary ray of the frame, rows in
// parallel, each pixel's linear RGBA from trace(ray).
#pragma once

#include <tbb/parallel_for.h>

#include <array>

#include "viewer/core/camera.h"
#include "viewer/core/image.h"
#include "viewer/core/render_settings.h"

namespace voxlink::viewer {

template <class Trace>
Image renderRows(const Camera& camera, const RenderSettings& settings, const Trace& trace) {
  Image image(settings.width, settings.height);
  tbb::parallel_for(uint32_t{0}, settings.height, [&](uint32_t y) {
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
