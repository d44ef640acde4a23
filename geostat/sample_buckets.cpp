// SPDX-License-Identifier: BSD-3-Clause
#include "geostat/detail/sample_buckets.h"

#include <algorithm>
#include <cmath>

namespace voxlink::geostat {

// The reach is widened by a hair so that rounding in the cell arithmetic never drops a sample
// whose computed distance is just below it.
SampleBuckets::SampleBuckets(const std::vector<Point3>& points, double reach)
    : reach_(reach * (1 + 1e-9)) {
  std::array<double, 3> high{};
  for (int a = 0; a < 3; ++a) {
    low_[a] = points.empty() ? 0 : points[0][a];
    high[a] = low_[a];
  }
  for (const Point3& p : points)
    for (int a = 0; a < 3; ++a) {
      low_[a] = std::min(low_[a], p[a]);
      high[a] = std::max(high[a], p[a]);
    }
  // At most ~2 cells per sample in all: a tiny reach over a wide extent would otherwise ask
  // for more cells than memory holds.
  const double maxCells = 2.0 * static_cast<double>(points.size()) + 8;
  double total = 1;
  for (int a = 0; a < 3; ++a) {
    cell_[a] = std::max(reach_, (high[a] - low_[a]) * 1e-9 + 1e-300);
    total *= std::floor((high[a] - low_[a]) / cell_[a]) + 1;
  }
  if (total > maxCells) {
    const double grow = std::cbrt(total / maxCells) * 1.01;
    for (int a = 0; a < 3; ++a) cell_[a] *= grow;
  }
  for (int a = 0; a < 3; ++a)
    cells_[a] = static_cast<int64_t>(std::floor((high[a] - low_[a]) / cell_[a])) + 1;
  const size_t count = static_cast<size_t>(cells_[0] * cells_[1] * cells_[2]);
  std::vector<uint32_t> cellOf(points.size());
  start_.assign(count + 1, 0);
  for (size_t i = 0; i < points.size(); ++i) {
    int64_t c[3];
    for (int a = 0; a < 3; ++a)
      c[a] = std::min<int64_t>(cells_[a] - 1,
                               static_cast<int64_t>((points[i][a] - low_[a]) / cell_[a]));
    cellOf[i] = static_cast<uint32_t>((c[2] * cells_[1] + c[1]) * cells_[0] + c[0]);
    ++start_[cellOf[i] + 1];
  }
  for (size_t c = 0; c < count; ++c) start_[c + 1] += start_[c];
  items_.resize(points.size());
  std::vector<uint32_t> fill(start_.begin(), start_.end() - 1);
  for (size_t i = 0; i < points.size(); ++i) items_[fill[cellOf[i]]++] = static_cast<uint32_t>(i);
}

void SampleBuckets::candidates(const Point3& q, std::vector<uint32_t>& out) const {
  int64_t from[3], to[3];
  for (int a = 0; a < 3; ++a) {
    const double lo = std::floor((q[a] - reach_ - low_[a]) / cell_[a]);
    const double hi = std::floor((q[a] + reach_ - low_[a]) / cell_[a]);
    if (hi < 0 || lo > static_cast<double>(cells_[a] - 1)) return;
    from[a] = static_cast<int64_t>(std::max(0.0, lo));  // clamped before the cast
    to[a] = static_cast<int64_t>(std::min(static_cast<double>(cells_[a] - 1), hi));
  }
  for (int64_t z = from[2]; z <= to[2]; ++z)
    for (int64_t y = from[1]; y <= to[1]; ++y) {
      const int64_t row = (z * cells_[1] + y) * cells_[0];
      out.insert(out.end(), items_.begin() + start_[static_cast<size_t>(row + from[0])],
                 items_.begin() + start_[static_cast<size_t>(row + to[0] + 1)]);
    }
}

}  // namespace voxlink::geostat
