// SPDX-License-Identifier: BSD-3-Clause
// The paired 32-neighbour solves (spd::solveNodes32) and the kept sets with the drift's extra
// products (linear, quadratic and external drift) and with simple kriging under a search radius:
// k around 32 on grids that are no brick multiple, one row and one node, each grid equal to
// Kriger::predict at every node and one thread's bits equal to two and three threads'.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "geostat/krige_grid.h"
#include "tests/geostat/kriging_test_util.h"

namespace voxlink::geostat {
namespace {

using test::kriger;
using test::model;
using test::randomPoints;

// A smooth external drift, at samples and nodes alike.
double driftAt(const Point3& p) { return 0.05 * p[0] - 0.02 * p[1] + std::sin(0.1 * p[0]); }

void expectGridEqualsPredict(const Kriger& k, const GridSpec& grid, const std::string& what) {
  SCOPED_TRACE(what);
  std::vector<double> drift;
  if (k.options().externalDrift)
    for (uint32_t z = 0; z < grid.dims[2]; ++z)
      for (uint32_t y = 0; y < grid.dims[1]; ++y)
        for (uint32_t x = 0; x < grid.dims[0]; ++x) drift.push_back(driftAt(grid.node(x, y, z)));
  const double* d = drift.empty() ? nullptr : drift.data();
  const test::KrigedGrid one = test::krigeInMemory(k, grid, {.threads = 1, .externalDrift = d});
  ASSERT_EQ(one.values.size(), grid.nodeCount());
  for (unsigned threads : {2u, 3u}) {
    const test::KrigedGrid more =
        test::krigeInMemory(k, grid, {.threads = threads, .externalDrift = d});
    ASSERT_EQ(more.values.size(), grid.nodeCount());
    EXPECT_EQ(0, std::memcmp(one.values.data(), more.values.data(), 8 * one.values.size()))
        << threads << " threads";
    EXPECT_EQ(0, std::memcmp(one.variances.data(), more.variances.data(), 8 * one.values.size()))
        << threads << " threads";
  }
  KrigingWorkspace ws;
  int reported = 0;
  for (uint32_t z = 0; z < grid.dims[2]; ++z)
    for (uint32_t y = 0; y < grid.dims[1]; ++y)
      for (uint32_t x = 0; x < grid.dims[0]; ++x) {
        const uint64_t at = (uint64_t{z} * grid.dims[1] + y) * grid.dims[0] + x;
        const Point3 node = grid.node(x, y, z);
        auto p = k.predict(node, ws, -1, d ? driftAt(node) : NAN);
        ASSERT_TRUE(p) << p.message();
        const double v = one.values[at], s = one.variances[at];
        const bool ok = std::fabs(v - p->value) <= 1e-8 * 10 &&
                        std::fabs(s - p->variance) <= 1e-8 * k.variogram().sill();
        if (!ok && reported++ < 5)
          ADD_FAILURE() << "node " << x << "," << y << "," << z << ": grid " << v << " / " << s
                        << ", predict " << p->value << " / " << p->variance << " (" << p->neighbours
                        << " neighbours)";
      }
}

const GridSpec kGrids[] = {{{19, 13, 1}, {-4, 3, 0}, {5.5, 7.5, 1}},
                           {{37, 1, 1}, {0, 50, 0}, {2.7, 1, 1}},
                           {{1, 1, 1}, {40, 60, 0}, {1, 1, 1}}};

TEST(GridPathsDrift, PolynomialAndExternalDriftAroundThirtyTwoNeighbours) {
  PointSet s = randomPoints(400, 77, 100, 2);
  for (size_t i = 0; i < s.size(); ++i) s.drift.push_back(driftAt(s.coords[i]));
  const Variogram v = model(VariogramType::kSpherical, 0.3, 8, 45);
  for (DriftKind drift : {DriftKind::kNone, DriftKind::kLinear, DriftKind::kQuadratic})
    for (bool external : {false, true})
      for (size_t k : {size_t{31}, size_t{32}, size_t{33}, size_t{48}})
        for (const GridSpec& grid : kGrids)
          expectGridEqualsPredict(
              kriger(s, v, {.maxNeighbours = k, .drift = drift, .externalDrift = external}), grid,
              "drift " + std::to_string(int(drift)) + " external " + std::to_string(external) +
                  " k " + std::to_string(k) + " dims " + std::to_string(grid.dims[0]) + "x" +
                  std::to_string(grid.dims[1]));
}

TEST(GridPathsDrift, SimpleKrigingOfThirtyTwoWithinASearchRadius) {
  const PointSet s = randomPoints(300, 78, 100, 2);
  const Variogram v = model(VariogramType::kExponential, 0.1, 5, 30);
  for (double reach : {double(INFINITY), 9.0, 15.0})
    for (size_t k : {size_t{31}, size_t{32}, size_t{64}})
      for (const GridSpec& grid : kGrids)
        expectGridEqualsPredict(kriger(s, v,
                                       {.kind = KrigingKind::kSimple,
                                        .simpleMean = 10,
                                        .maxNeighbours = k,
                                        .maxDistance = reach}),
                                grid,
                                "reach " + std::to_string(reach) + " k " + std::to_string(k) +
                                    " dims " + std::to_string(grid.dims[0]));
}

}  // namespace
}  // namespace voxlink::geostat
