// SPDX-License-Identifier: BSD-3-Clause
// krigeGrid's block solvers (local bricks with shared factorizations, global level-3 BLAS) must
// give what Kriger::predict gives node by node: the same neighbour sets, the same estimates and
// variances to rounding, whatever the threads, slab depth, radius or kind.
#include <gtest/gtest.h>

#include <cmath>

#include "geostat/krige_grid.h"
#include "tests/geostat/kriging_test_util.h"
#include "tests/geostat/walker_lake_data.h"

namespace voxlink::geostat {
namespace {

using test::kriger;
using test::model;
using test::randomPoints;

struct Worst {
  double value = 0, variance = 0;
  uint64_t noData = 0;
};

// Largest |grid - predict| over every node, relative to `scale` (values) and the sill.
Worst compareWithPredict(const Kriger& k, const GridSpec& grid, double scale, unsigned threads) {
  const test::KrigedGrid got = test::krigeInMemory(k, grid, {.threads = threads});
  Worst w;
  KrigingWorkspace ws;
  for (uint32_t z = 0; z < grid.dims[2]; ++z)
    for (uint32_t y = 0; y < grid.dims[1]; ++y)
      for (uint32_t x = 0; x < grid.dims[0]; ++x) {
        const uint64_t at = (uint64_t{z} * grid.dims[1] + y) * grid.dims[0] + x;
        auto p = k.predict(grid.node(x, y, z), ws);
        EXPECT_TRUE(p) << p.message();
        if (!p->hasData) {
          EXPECT_TRUE(std::isnan(got.values[at]) && std::isnan(got.variances[at])) << at;
          ++w.noData;
          continue;
        }
        // A NaN difference is a failure (std::max would drop it).
        const double dv = std::fabs(got.values[at] - p->value) / scale;
        const double dvar = std::fabs(got.variances[at] - p->variance) / k.variogram().sill();
        w.value = std::isnan(dv) ? INFINITY : std::max(w.value, dv);
        w.variance = std::isnan(dvar) ? INFINITY : std::max(w.variance, dvar);
      }
  return w;
}

TEST(GridPaths, WalkerLakeLocalAndGlobalEqualPredictAtEveryNode) {
  VOXLINK_REQUIRE_DATA(test::kWalkerSamples);
  const PointSet s = test::walkerSamples();
  const Variogram v = model(VariogramType::kSpherical, 22144, 70207.9, 35.085);
  const GridSpec grid{{130, 150, 1}, {1, 1, 0}, {2, 2, 1}};
  for (size_t neighbours : {size_t{1}, size_t{16}, size_t{32}, size_t{0}}) {
    const Worst w = compareWithPredict(kriger(s, v, {.maxNeighbours = neighbours}), grid, 300, 2);
    EXPECT_LE(w.value, 1e-10) << neighbours;
    EXPECT_LE(w.variance, 1e-10) << neighbours;
  }
}

TEST(GridPaths, ThreeDimensionalBricksAndSlabsEqualPredict) {
  const PointSet s = randomPoints(3000, 11, 100.0, 3);
  const Variogram v = model(VariogramType::kExponential, 0.5, 8, 30);
  // 37 slices: slabs of 8 and a last one of 5; 41 x 43 nodes: partial bricks on both axes.
  const GridSpec grid{{41, 43, 37}, {-3, 1, 2}, {2.5, 2.4, 2.7}};
  for (unsigned threads : {1u, 2u}) {
    const Worst w = compareWithPredict(kriger(s, v, {.maxNeighbours = 24}), grid, 3, threads);
    EXPECT_LE(w.value, 1e-10);
    EXPECT_LE(w.variance, 1e-10);
  }
}

TEST(GridPaths, SearchRadiusSimpleKrigingAndNodesWithoutData) {
  const PointSet s = randomPoints(400, 5);
  const Variogram v = model(VariogramType::kGaussian, 0.2, 9, 40);
  const GridSpec grid{{60, 50, 1}, {-40, -30, 0}, {3, 3.5, 1}};  // reaches far outside the data
  for (KrigingKind kind : {KrigingKind::kOrdinary, KrigingKind::kSimple})
    for (size_t neighbours : {size_t{12}, size_t{0}}) {
      const Kriger k = kriger(
          s, v, {.kind = kind, .simpleMean = 10, .maxNeighbours = neighbours, .maxDistance = 15});
      const Worst w = compareWithPredict(k, grid, 3, 2);
      EXPECT_LE(w.value, 1e-10);
      EXPECT_LE(w.variance, 1e-10);
      if (kind == KrigingKind::kOrdinary) {
        EXPECT_GT(w.noData, 100u);
      }
    }
}

TEST(GridPaths, CrowdedSamplesFarFromTheGridSplitBricksDownToSingleNodes) {
  // 2000 samples in a 1 x 1 square, the grid 1000 units away: every brick's candidate ball
  // holds all samples, so bricks split until single nodes query the tree directly.
  PointSet s = randomPoints(2000, 3, 1.0);
  const Variogram v = model(VariogramType::kExponential, 0.1, 9, 3000);
  const GridSpec grid{{9, 7, 1}, {1000, 1000, 0}, {10, 10, 1}};
  const Worst w = compareWithPredict(kriger(s, v, {.maxNeighbours = 16}), grid, 3, 2);
  EXPECT_LE(w.value, 1e-8);
  EXPECT_LE(w.variance, 1e-8);
}

}  // namespace
}  // namespace voxlink::geostat
