// SPDX-License-Identifier: BSD-3-Clause
// The pixel loop the float64 reference renderers share: every primary ray of the frame, rows in
// parallel, each pixel's linear RGBA from trace(ray).
#pragma once

#include <array>

#include "base/parallel_for.h"
#include "render/camera.h"
#include "render/image.h"
#include "render/render_settings.h"

namespace voxlink::render {

template <class Trace>
Image renderRows(const Camera& camera, const RenderSettings& settings, const Trace& trace) {
  Image image(settings.width, settings.height);
  base::parallelFor(settings.height, 0, [&](uint64_t row) {
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

}  // namespace voxlink::render
