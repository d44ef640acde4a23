// SPDX-License-Identifier: BSD-3-Clause
// Universal kriging's hard cases (drift.h): a drift that is degenerate over a neighbourhood
// (samples on a line under a linear drift, an external drift with one value) is reduced, never
// NaN, through Kriger::predict and both grid solvers; UTM-sized coordinates lose nothing.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "geostat/krige_grid.h"
#include "tests/geostat/kriging_test_util.h"

namespace voxlink::geostat {
namespace {

using test::kriger;
using test::model;
using test::randomPoints;

using Grid = test::KrigedGrid;

Grid krige(const Kriger& k, const GridSpec& grid, const double* externalDrift = nullptr) {
  return test::krigeInMemory(k, grid, {.threads = 2, .externalDrift = externalDrift});
}

// Samples on the line y = 2 x with values 3 + 0.5 x: under a linear drift the y term is
// x's double over every neighbourhood and is dropped; the linear trend along the line is then
// reproduced exactly, between the samples and beyond them.
TEST(DriftHardCases, CollinearSamplesUnderALinearDriftDropTheDependentTerm) {
  PointSet s;
  for (int i = 0; i < 40; ++i) {
    const double x = 2.5 * i + 0.3 * std::sin(i);
    s.coords.push_back({x, 2 * x, 0});
    s.values.push_back(3 + 0.5 * x + std::cos(1.7 * i));  // trend plus a residual
  }
  const Variogram v = model(VariogramType::kExponential, 0.1, 1, 30);
  for (size_t neighbours : {size_t{0}, size_t{8}}) {
    const Kriger k = kriger(s, v, {.maxNeighbours = neighbours, .drift = DriftKind::kLinear});
    KrigingWorkspace ws;
    auto p = k.predict({51.1, 102.2, 0}, ws);
    ASSERT_TRUE(p) << p.message();
    EXPECT_TRUE(std::isfinite(p->value) && std::isfinite(p->variance));
    EXPECT_EQ(p->driftTermsDropped, 1u);
    // Far beyond the samples the estimate follows the fitted trend along the line, which a
    // constant mean (ordinary kriging) would not.
    auto far = k.predict({400, 800, 0}, ws);
    ASSERT_TRUE(far);
    EXPECT_GT(far->value, 150) << neighbours;
    // Off the line too: every node of a grid is finite, on both grid paths, and counted.
    GridSpec grid;
    grid.dims = {24, 20, 1};
    grid.spacing = {5, 10, 1};
    const Grid g = krige(k, grid);
    ASSERT_EQ(g.values.size(), grid.nodeCount());
    for (size_t i = 0; i < g.values.size(); ++i) {
      ASSERT_TRUE(std::isfinite(g.values[i]) && std::isfinite(g.variances[i])) << i;
      auto q = k.predict(grid.node(uint32_t(i % 24), uint32_t(i / 24), 0), ws);
      ASSERT_TRUE(q);
      EXPECT_NEAR(g.values[i], q->value, 1e-9 * 100) << i;
      EXPECT_NEAR(g.variances[i], q->variance, 1e-9) << i;
    }
    EXPECT_EQ(g.summary.driftReducedNodes, grid.nodeCount()) << neighbours;
    EXPECT_NE(g.summary.text().find("without drift terms"), std::string::npos);
  }
}

// An external drift with one value over a neighbourhood is the constant term again: it is
// dropped there, and the node gets the ordinary kriging answer, whatever the node's own
// drift value.
TEST(DriftHardCases, ExternalDriftConstantOverANeighbourhoodFallsBackToOrdinaryKriging) {
  PointSet s = randomPoints(300, 5);
  for (size_t i = 0; i < s.size(); ++i)  // 7 in the left half, varying in the right half
    s.drift.push_back(s.coords[i][0] < 50 ? 7.0 : 0.1 * s.coords[i][0] + std::sin(double(i)));
  const Variogram v = model(VariogramType::kSpherical, 0.5, 8, 40);
  const Kriger ked = kriger(s, v, {.maxNeighbours = 12, .externalDrift = true});
  const Kriger ok = kriger(s, v, {.maxNeighbours = 12});
  GridSpec grid;
  grid.dims = {11, 21, 1};
  grid.spacing = {2, 5, 1};
  grid.origin = {10, 0, 0};  // x 10..30: every neighbourhood inside the constant half
  std::vector<double> nodeDrift(grid.nodeCount());
  for (size_t i = 0; i < nodeDrift.size(); ++i) nodeDrift[i] = 9 + 0.01 * double(i);
  const Grid g = krige(ked, grid, nodeDrift.data());
  const Grid reference = krige(ok, grid);
  KrigingWorkspace ws;
  for (size_t i = 0; i < g.values.size(); ++i) {
    ASSERT_TRUE(std::isfinite(g.values[i]) && std::isfinite(g.variances[i])) << i;
    EXPECT_NEAR(g.values[i], reference.values[i], 1e-9 * 10) << i;
    EXPECT_NEAR(g.variances[i], reference.variances[i], 1e-9 * 8) << i;
    auto p = ked.predict(grid.node(uint32_t(i % 11), uint32_t(i / 11), 0), ws, -1, nodeDrift[i]);
    ASSERT_TRUE(p);
    EXPECT_EQ(p->driftTermsDropped, 1u);
    EXPECT_NEAR(p->value, g.values[i], 1e-9 * 10) << i;
  }
  EXPECT_EQ(g.summary.driftReducedNodes, grid.nodeCount());
  // In the right half the drift varies and is used: the answer differs from ordinary kriging.
  auto right = ked.predict({80, 50, 0}, ws, -1, 30.0);
  auto rightOk = ok.predict({80, 50, 0}, ws);
  ASSERT_TRUE(right && rightOk);
  EXPECT_EQ(right->driftTermsDropped, 0u);
  EXPECT_GT(std::fabs(right->value - rightOk->value), 1e-3);
}

// A quadratic drift at UTM-sized coordinates (4.5e6, 5.2e6) gives what it gives at the
// origin: the drift terms are centred and scaled (x^2 ~ 2.7e13 unscaled would leave G with a
// condition near 1e26).
TEST(DriftHardCases, QuadraticDriftAtUtmCoordinatesEqualsTheUnshiftedProblem) {
  const PointSet near = randomPoints(400, 9, 1000.0);
  PointSet far = near;
  for (Point3& p : far.coords) p = {p[0] + 4.5e6, p[1] + 5.2e6, 0};
  const Variogram v = model(VariogramType::kExponential, 0.2, 9, 300);
  for (size_t neighbours : {size_t{0}, size_t{32}}) {
    const Kriger a = kriger(near, v, {.maxNeighbours = neighbours, .drift = DriftKind::kQuadratic});
    const Kriger b = kriger(far, v, {.maxNeighbours = neighbours, .drift = DriftKind::kQuadratic});
    GridSpec grid;
    grid.dims = {30, 30, 1};
    grid.spacing = {34, 34, 1};
    GridSpec shifted = grid;
    shifted.origin = {4.5e6, 5.2e6, 0};
    const Grid ga = krige(a, grid), gb = krige(b, shifted);
    for (size_t i = 0; i < ga.values.size(); ++i) {
      ASSERT_TRUE(std::isfinite(gb.values[i]) && std::isfinite(gb.variances[i])) << i;
      EXPECT_NEAR(ga.values[i], gb.values[i], 1e-7 * 10) << i;
      EXPECT_NEAR(ga.variances[i], gb.variances[i], 1e-7 * 9) << i;
    }
    EXPECT_EQ(gb.summary.driftReducedNodes, 0u);
  }
}

// A search radius can leave fewer samples than a quadratic drift has terms (6 in 2-D): the
// terms the samples cannot carry are dropped; one sample in reach gives its own value.
TEST(DriftHardCases, FewerSamplesInReachThanDriftTermsKeepTheTermsTheyCanCarry) {
  const PointSet s = randomPoints(60, 17);
  const Variogram v = model(VariogramType::kExponential, 0.3, 5, 20);
  const Kriger k =
      kriger(s, v, {.maxNeighbours = 12, .maxDistance = 9, .drift = DriftKind::kQuadratic});
  GridSpec grid;
  grid.dims = {50, 50, 1};
  grid.spacing = {2, 2, 1};
  const Grid g = krige(k, grid);
  KrigingWorkspace ws;
  size_t withData = 0, reduced = 0, single = 0;
  for (size_t i = 0; i < g.values.size(); ++i) {
    auto p = k.predict(grid.node(uint32_t(i % 50), uint32_t(i / 50), 0), ws);
    ASSERT_TRUE(p) << p.message();
    if (!p->hasData) {
      EXPECT_TRUE(std::isnan(g.values[i])) << i;  // the no-data value, counted
      continue;
    }
    ++withData;
    ASSERT_TRUE(std::isfinite(g.values[i]) && std::isfinite(g.variances[i])) << i;
    // Six terms fitted to barely more samples extrapolate wildly (|value| up to ~2400 from
    // data of mean 10, sd 3) through a badly conditioned G: agreement is relative.
    EXPECT_NEAR(g.values[i], p->value, 1e-6 * std::max(10.0, std::fabs(p->value))) << i;
    reduced += p->driftTermsDropped > 0;
    if (p->neighbours == 1) {
      ++single;
      EXPECT_EQ(p->driftTermsDropped, 5u);
      EXPECT_NEAR(p->value, s.values[ws.key[0]], 1e-9 * 10) << i;
    }
  }
  EXPECT_GT(withData, g.values.size() / 2);
  EXPECT_GT(single, 0u);
  EXPECT_EQ(g.summary.driftReducedNodes, reduced);
  EXPECT_GT(reduced, 0u);
}

TEST(DriftHardCases, SimpleKrigingWithADriftAndAMissingDriftColumnAreRefused) {
  const PointSet s = randomPoints(20, 3);
  const Variogram v = model(VariogramType::kExponential, 0, 1, 30);
  auto sk = Kriger::make(
      s, v, {.kind = KrigingKind::kSimple, .simpleMean = 0, .drift = DriftKind::kLinear});
  ASSERT_FALSE(sk);
  EXPECT_NE(sk.message().find("--kind ok"), std::string::npos) << sk.message();
  auto noColumn = Kriger::make(s, v, {.externalDrift = true});
  ASSERT_FALSE(noColumn);
  EXPECT_NE(noColumn.message().find("no drift column"), std::string::npos);
  // A grid without the drift's node values is refused, not kriged with garbage.
  PointSet withDrift = s;
  withDrift.drift.assign(s.size(), 1.0);
  for (size_t i = 0; i < s.size(); ++i) withDrift.drift[i] = s.coords[i][0];
  const Kriger ked = kriger(withDrift, v, {.externalDrift = true});
  GridSpec grid;
  auto r = krigeGrid(ked, grid,
                     [](uint32_t, uint32_t, const double*, const double*) { return Status::ok(); });
  ASSERT_FALSE(r);
  EXPECT_NE(r.message().find("external drift"), std::string::npos);
}

}  // namespace
}  // namespace voxlink::geostat
