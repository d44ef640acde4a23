// SPDX-License-Identifier: BSD-3-Clause
// Small point sets for the kriging tests, and a grid kriged into memory.
#pragma once

#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "geostat/detail/kriging.h"
#include "geostat/krige_grid.h"

namespace voxlink::geostat::test {

inline PointSet randomPoints(size_t n, uint32_t seed, double extent = 100.0, int dimension = 2) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0, extent);
  std::normal_distribution<double> value(10, 3);
  PointSet s;
  s.dimension = dimension;
  for (size_t i = 0; i < n; ++i) {
    s.coords.push_back({u(rng), u(rng), dimension == 3 ? u(rng) : 0.0});
    s.values.push_back(value(rng));
  }
  return s;
}

inline Variogram model(VariogramType type, double nugget, double psill, double range,
                       double nu = 0.5) {
  return Variogram::make({type, nugget, psill, range, nu}).value();
}

inline Kriger kriger(const PointSet& s, const Variogram& v, KrigingOptions o = {}) {
  auto k = Kriger::make(s, v, o);
  if (!k) throw std::runtime_error(k.message());
  return std::move(k).value();
}

// Every node's value and variance (x fastest) and the run's summary.
struct KrigedGrid {
  std::vector<double> values, variances;
  KrigingSummary summary;
};

// krigeGrid into memory; a failed run or a short grid fails the calling test.
inline KrigedGrid krigeInMemory(const Kriger& k, const GridSpec& grid,
                                const GridKrigingOptions& options) {
  KrigedGrid out;
  auto summary = krigeGrid(
      k, grid,
      [&](uint32_t, uint32_t count, const double* v, const double* s) -> Status {
        out.values.insert(out.values.end(), v, v + count * grid.sliceNodes());
        out.variances.insert(out.variances.end(), s, s + count * grid.sliceNodes());
        return Status::ok();
      },
      options);
  EXPECT_TRUE(summary) << summary.message();
  if (summary) out.summary = *summary;
  EXPECT_EQ(out.values.size(), grid.nodeCount());
  return out;
}

}  // namespace voxlink::geostat::test
