// SPDX-License-Identifier: BSD-3-Clause
// docs/kriging.md: nodes with no sample within --max-distance are written as --nodata, but
// simple kriging gives the known mean and the sill there, as Kriger::predict does (before the
// fix the grid solvers wrote --nodata for simple kriging too).
#include <gtest/gtest.h>

#include <cmath>

#include "geostat/krige_grid.h"
#include "tests/geostat/kriging_test_util.h"

namespace voxlink::geostat {
namespace {

TEST(SimpleKrigingWithoutData, NodesOutOfReachHoldTheMeanAndTheSillAsPredictGives) {
  for (int dimension : {2, 3})
    for (size_t k : {size_t{0}, size_t{16}}) {
      const PointSet s = test::randomPoints(300, 91, 100, dimension);
      const Variogram v = test::model(VariogramType::kSpherical, 0.3, 6, 25);
      const Kriger kr = test::kriger(
          s, v,
          {.kind = KrigingKind::kSimple, .simpleMean = 10, .maxNeighbours = k, .maxDistance = 6});
      const GridSpec grid{{15, 13, dimension == 2 ? 1u : 7u}, {-30, -20, 0}, {12, 13, 15}};
      const test::KrigedGrid g = test::krigeInMemory(kr, grid, {.threads = 2});
      EXPECT_GT(g.summary.nodesWithoutData, 0u);
      KrigingWorkspace ws;
      int reported = 0;
      for (uint32_t z = 0; z < grid.dims[2]; ++z)
        for (uint32_t y = 0; y < grid.dims[1]; ++y)
          for (uint32_t x = 0; x < grid.dims[0]; ++x) {
            const uint64_t at = (uint64_t{z} * grid.dims[1] + y) * grid.dims[0] + x;
            auto p = kr.predict(grid.node(x, y, z), ws);
            ASSERT_TRUE(p) << p.message();
            ASSERT_TRUE(p->hasData);  // simple kriging always has an answer
            const bool same = std::fabs(g.values[at] - p->value) <= 1e-9 * 10 &&
                              std::fabs(g.variances[at] - p->variance) <= 1e-9 * 6.3;
            if (!same && reported++ < 3)
              ADD_FAILURE() << "dimension " << dimension << " k " << k << " node " << x << "," << y
                            << "," << z << ": grid " << g.values[at] << " / " << g.variances[at]
                            << ", predict " << p->value << " / " << p->variance << " ("
                            << p->neighbours << " neighbours)";
          }
    }
}

}  // namespace
}  // namespace voxlink::geostat
