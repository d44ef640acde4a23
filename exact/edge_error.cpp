// SPDX-License-Identifier: BSD-3-Clause
#include "exact/edge_error.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "base/parallel_for.h"

namespace voxlink::exact {

namespace {

bool differsFromNeighbour(const FirstHitMap& m, uint32_t x, uint32_t y) {
  const int32_t here = m.material[size_t{y} * m.width + x];
  const int dx[4] = {1, -1, 0, 0}, dy[4] = {0, 0, 1, -1};
  for (int k = 0; k < 4; ++k) {
    const int64_t nx = int64_t(x) + dx[k], ny = int64_t(y) + dy[k];
    if (nx < 0 || ny < 0 || nx >= m.width || ny >= m.height) continue;
    if (m.material[size_t(ny) * m.width + size_t(nx)] != here) return true;
  }
  return false;
}

double psnrOf(double squaredSum, uint64_t samples) {
  if (samples == 0) return std::numeric_limits<double>::quiet_NaN();
  const double mse = squaredSum / double(samples);
  return mse > 0 ? -10.0 * std::log10(mse) : std::numeric_limits<double>::infinity();
}

}  // namespace

FirstHitMap firstHits(const render::SceneWalker& scene, const render::Camera& camera,
                      uint32_t width, uint32_t height) {
  FirstHitMap map{width, height, std::vector<int32_t>(size_t{width} * height, kNoHit)};
  base::parallelFor(height, 0, [&](uint64_t row) {
    const auto y = static_cast<uint32_t>(row);
    for (uint32_t x = 0; x < width; ++x)
      scene.walk(camera.primaryRay(x, y, width, height), 0.0, HUGE_VAL,
                 [&](const render::SceneEvent& e) {
                   if (e.kind != render::SceneEvent::Kind::kSurface) return true;
                   map.material[size_t{y} * width + x] = int32_t(e.material);
                   return false;
                 });
  });
  return map;
}

Result<EdgeError> compareEdges(const render::Image& test, const render::Image& truth,
                               const FirstHitMap& a, const FirstHitMap& b) {
  const uint32_t w = truth.width, h = truth.height;
  if (test.width != w || test.height != h || a.width != w || a.height != h || b.width != w ||
      b.height != h)
    return makeError(ErrorCode::kInvalidArgument, "edge error: images and first-hit maps of ",
                     "different sizes");
  uint64_t mismatch = 0, coverage = 0, edges = 0;
  double edgeSum = 0, interiorSum = 0;
  for (uint32_t y = 0; y < h; ++y)
    for (uint32_t x = 0; x < w; ++x) {
      const size_t i = size_t{y} * w + x;
      mismatch += a.material[i] != b.material[i];
      coverage += (a.material[i] == kNoHit) != (b.material[i] == kNoHit);
      double squared = 0;
      for (int c = 0; c < 3; ++c) {
        const double d = std::clamp(double(test.pixel(x, y)[c]), 0.0, 1.0) -
                         std::clamp(double(truth.pixel(x, y)[c]), 0.0, 1.0);
        squared += d * d;
      }
      if (differsFromNeighbour(a, x, y) || differsFromNeighbour(b, x, y)) {
        ++edges;
        edgeSum += squared;
      } else {
        interiorSum += squared;
      }
    }
  const double pixels = double(w) * h;
  EdgeError e;
  e.firstHitMismatch = mismatch / pixels;
  e.coverageMismatch = coverage / pixels;
  e.edgeShare = edges / pixels;
  e.edgePsnr = psnrOf(edgeSum, 3 * edges);
  e.interiorPsnr = psnrOf(interiorSum, 3 * (uint64_t(w) * h - edges));
  return e;
}

}  // namespace voxlink::exact
