// SPDX-License-Identifier: BSD-3-Clause
#include "viewer/app/detail/object_pick.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace voxlink::viewer {

std::optional<double> rayEntersBox(const render::Ray& ray, const render::Box& box) {
  double near = 0, far = std::numeric_limits<double>::infinity();
  for (int a = 0; a < 3; ++a) {
    const double o = ray.origin[a], d = ray.direction[a];
    if (std::abs(d) < 1e-12) {  // parallel to the slab: inside it or never
      if (o < box.lo[a] || o > box.hi[a]) return std::nullopt;
      continue;
    }
    double t0 = (box.lo[a] - o) / d, t1 = (box.hi[a] - o) / d;
    if (t0 > t1) std::swap(t0, t1);
    near = std::max(near, t0);
    far = std::min(far, t1);
    if (near > far) return std::nullopt;
  }
  return near;
}

std::optional<size_t> pickBox(const render::Camera& camera, double px, double py, uint32_t width,
                              uint32_t height, const std::vector<render::Box>& boxes) {
  if (!(px >= 0 && py >= 0 && px < width && py < height)) return std::nullopt;
  const render::Ray ray = camera.primaryRay(uint32_t(px), uint32_t(py), width, height);
  std::optional<size_t> best;
  double nearest = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < boxes.size(); ++i)
    if (auto t = rayEntersBox(ray, boxes[i]); t && *t < nearest) {
      nearest = *t;
      best = i;
    }
  return best;
}

}  // namespace voxlink::viewer
