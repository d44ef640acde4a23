// SPDX-License-Identifier: BSD-3-Clause
// Pass 1 of the converter: how many voxels each brick keeps, templated on the source element
// type T and the keep rule (keep_rule.h). A job is one row of bricks (fixed bz, by; all bx), so
// the split of work does not depend on slab size or thread count, and neither does the output.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <type_traits>
#include <vector>

#include "convert/detail/slab_window.h"
#include "format/layout.h"

namespace voxlink::convert {

// The brick grid of one conversion (both passes).
struct GridShape {
  uint32_t dims[3];
  uint32_t n;
  uint32_t grid[3];
  format::AxisFrame frame;
  double spacing[3];
};

// One job of either pass: the row of bricks (bz, by) of the loaded slab window.
struct BrickRow {
  const SlabWindow& window;
  const GridShape& grid;
  uint32_t bz, by;
};

// Pass 1 output of one job.
struct CountResult {
  double keptMin = std::numeric_limits<double>::infinity();
  double keptMax = -std::numeric_limits<double>::infinity();
  // f64 sources only: the smallest nonzero |value| kept (the f32 scale must reach down to it).
  double keptMinMagnitude = std::numeric_limits<double>::infinity();
  bool nonFinite = false;
  uint32_t nonFiniteAt[3] = {0, 0, 0};
  double nonFiniteValue = 0;
};

// Counts kept voxels of the bricks in row (row.bz, row.by) into counts[bx]. `trackRange` asks for
// the min and max kept value (not needed for 8-bit sources, whose mapping does not depend on it).
// The keep flags of all n*n x-lines of the brick row are summed per x first (a loop the
// compiler vectorizes), then per brick.
template <class T, class Keep>
void countBrickRow(const BrickRow& brickRow, const Keep& keep, bool trackRange, uint16_t* counts,
                   CountResult& result) {
  const SlabWindow& window = brickRow.window;
  const GridShape& g = brickRow.grid;
  const uint32_t bz = brickRow.bz, by = brickRow.by;
  const uint32_t n = g.n, nx = g.dims[0];
  const uint32_t z0 = bz * n, z1 = std::min(g.dims[2], z0 + n);
  const uint32_t y0 = by * n, y1 = std::min(g.dims[1], y0 + n);
  thread_local std::vector<uint16_t> perX;  // up to n*n = 1024 flags per x: fits 16 bits
  thread_local std::vector<uint8_t> perX8;  // the same for 8-bit sources and n <= 8
  const bool small = sizeof(T) == 1 && n * n <= 255 && !trackRange;
  perX.assign(nx, 0);
  if (small) perX8.assign(nx, 0);
  uint16_t* __restrict acc = perX.data();
  uint8_t* __restrict acc8 = perX8.data();
  const Keep test = keep;  // a local copy: stores to acc cannot alias it
  T keptMin = std::numeric_limits<T>::max(), keptMax = std::numeric_limits<T>::lowest();
  double tiny = std::numeric_limits<double>::infinity();
  constexpr bool kTrackMagnitude = std::is_same_v<T, double>;
  auto keepMagnitude = [&]([[maybe_unused]] bool k, [[maybe_unused]] T v) {
    if constexpr (kTrackMagnitude) {
      const double a = std::abs(v);
      tiny = k && a > 0 && a < tiny ? a : tiny;
    }
  };
  for (uint32_t z = z0; z < z1; ++z) {
    const T* slice = reinterpret_cast<const T*>(window.slice(z));
    const uint8_t* activeSlice = window.active(z);
    for (uint32_t y = y0; y < y1; ++y) {
      const T* __restrict row = slice + uint64_t{y} * nx;
      if constexpr (std::is_floating_point_v<T>) {
        bool finite = true;
        for (uint32_t x = 0; x < nx; ++x) finite &= std::isfinite(row[x]);
        if (!finite && !result.nonFinite) {
          uint32_t x = 0;
          while (std::isfinite(row[x])) ++x;
          result.nonFinite = true;
          result.nonFiniteAt[0] = x;
          result.nonFiniteAt[1] = y;
          result.nonFiniteAt[2] = z;
          result.nonFiniteValue = static_cast<double>(row[x]);
        }
        if (result.nonFinite) return;
      }
      if (activeSlice) {  // a source with inactive voxels (OpenVDB): those are never kept
        const uint8_t* active = activeSlice + uint64_t{y} * nx;
        for (uint32_t x = 0; x < nx; ++x) {
          const bool k = active[x] && test(row[x]);
          if (small)
            acc8[x] = static_cast<uint8_t>(acc8[x] + (k ? 1 : 0));
          else
            acc[x] = static_cast<uint16_t>(acc[x] + (k ? 1 : 0));
          keptMin = k && row[x] < keptMin ? row[x] : keptMin;
          keptMax = k && row[x] > keptMax ? row[x] : keptMax;
          keepMagnitude(k, row[x]);
        }
        continue;
      }
      if constexpr (sizeof(T) == 1) {
        // 8-bit sources: sum 64 lines at a time in 8-bit lanes (twice the lanes per vector),
        // then widen; n <= 8 bricks have at most 64 lines per row of bricks.
        if (small) {
          for (uint32_t x = 0; x < nx; ++x)
            acc8[x] = static_cast<uint8_t>(acc8[x] + (test(row[x]) ? 1 : 0));
          continue;
        }
      }
      for (uint32_t x = 0; x < nx; ++x)
        acc[x] = static_cast<uint16_t>(acc[x] + (test(row[x]) ? 1 : 0));
      if (trackRange) {
        for (uint32_t x = 0; x < nx; ++x) {
          const bool k = test(row[x]);
          keptMin = k && row[x] < keptMin ? row[x] : keptMin;
          keptMax = k && row[x] > keptMax ? row[x] : keptMax;
          keepMagnitude(k, row[x]);
        }
      }
    }
  }
  if (small)
    for (uint32_t x = 0; x < nx; ++x) acc[x] = acc8[x];
  for (uint32_t bx = 0, x0 = 0; x0 < nx; ++bx, x0 += n) {
    const uint32_t x1 = std::min(nx, x0 + n);
    uint32_t c = 0;
    for (uint32_t x = x0; x < x1; ++x) c += acc[x];
    counts[bx] = static_cast<uint16_t>(counts[bx] + c);
    if (trackRange && c) {
      result.keptMin = std::min(result.keptMin, static_cast<double>(keptMin));
      result.keptMax = std::max(result.keptMax, static_cast<double>(keptMax));
      result.keptMinMagnitude = std::min(result.keptMinMagnitude, tiny);
    }
  }
}

}  // namespace voxlink::convert
