// SPDX-License-Identifier: BSD-3-Clause
// The hard cases of issue 27 through the grid solvers (local bricks, global BLAS): each must
// give the answer Kriger::predict gives, finite, with its condition reported.
#include <gtest/gtest.h>

#include <cmath>

#include "geostat/krige_grid.h"
#include "tests/geostat/kriging_test_util.h"

namespace voxlink::geostat {
namespace {

using test::kriger;
using test::model;
using test::randomPoints;

using Grid = test::KrigedGrid;

Grid krige(const Kriger& k, const GridSpec& grid) {
  return test::krigeInMemory(k, grid, {.threads = 2});
}

// Every node finite and equal to Kriger::predict within `tolerance` (times `scale` for values,
// the sill for variances).
void expectSameAsPredict(const Kriger& k, const GridSpec& grid, const Grid& got, double scale,
                         double tolerance) {
  KrigingWorkspace ws;
  for (uint32_t y = 0; y < grid.dims[1]; ++y)
    for (uint32_t x = 0; x < grid.dims[0]; ++x) {
      const size_t at = size_t{y} * grid.dims[0] + x;
      ASSERT_TRUE(std::isfinite(got.values[at]) && std::isfinite(got.variances[at])) << at;
      auto p = k.predict(grid.node(x, y, 0), ws);
      ASSERT_TRUE(p) << p.message();
      EXPECT_NEAR(got.values[at], p->value, tolerance * scale) << at;
      EXPECT_NEAR(got.variances[at], p->variance, tolerance * k.variogram().sill()) << at;
    }
}

TEST(KrigingHardCases, UnmergedNearDuplicatesClimbTheSameJitterLadderAsPredict) {
  PointSet s = randomPoints(200, 21);
  for (size_t i = 0; i < 40; ++i) {  // 40 samples get a twin 1e-7 away with another value
    s.coords.push_back({s.coords[i][0] + 1e-7, s.coords[i][1], 0});
    s.values.push_back(s.values[i] + 0.5);
  }
  // Gaussian without nugget: twins 1e-7 apart make every system containing both singular
  // (an exponential model is only ill-conditioned, ~1e8, and needs no jitter).
  const Variogram v = model(VariogramType::kGaussian, 0, 9, 40);
  const GridSpec grid{{40, 40, 1}, {0, 0, 0}, {2.5, 2.5, 1}};
  for (size_t neighbours : {size_t{16}, size_t{0}}) {
    const Kriger k = kriger(s, v, {.maxNeighbours = neighbours, .mergeDistance = 0});
    const Grid g = krige(k, grid);
    EXPECT_GT(g.summary.regularizedNodes, 0u) << neighbours;
    EXPECT_GT(g.summary.largestJitter, 0.0) << neighbours;
    EXPECT_LE(g.summary.worstCondition, 1e12) << neighbours;
    EXPECT_GT(g.summary.worstCondition, 1e6) << neighbours;
    // Conditions near 1e12 amplify the rounding of two factorization orders (and may put a
    // system on the other side of a jitter step): measured up to 0.0092, i.e. 3e-3 sd.
    expectSameAsPredict(k, grid, g, 3, 5e-3);
  }
}

TEST(KrigingHardCases, GaussianWithoutNuggetLocallyEstimatesEveryCondition) {
  PointSet s;
  for (int i = 0; i < 30; ++i)
    for (int j = 0; j < 30; ++j) {
      s.coords.push_back({i * 1.0, j * 1.0, 0});
      s.values.push_back(std::sin(0.3 * i) + std::cos(0.2 * j));
    }
  const Kriger k = kriger(s, model(VariogramType::kGaussian, 0, 1, 30), {.maxNeighbours = 24});
  const GridSpec grid{{30, 30, 1}, {0.25, 0.25, 0}, {0.95, 0.95, 1}};
  const Grid g = krige(k, grid);
  // No nugget, and conditions too large for the bound from L^-1 to settle: all estimated.
  EXPECT_EQ(g.summary.systemsBounded, 0u);
  EXPECT_GT(g.summary.worstCondition, 1e6);
  EXPECT_LE(g.summary.worstCondition, 1e12);
  expectSameAsPredict(k, grid, g, 1, 1e-6);
}

TEST(KrigingHardCases, UtmCoordinatesOnTheGridEqualTheUnshiftedGrid) {
  const PointSet s = randomPoints(500, 22, 1000);
  PointSet shifted = s;
  for (auto& c : shifted.coords) {
    c[0] += 4.5e5;
    c[1] += 5.2e6;
  }
  const Variogram v = model(VariogramType::kSpherical, 0.5, 9, 300);
  for (size_t neighbours : {size_t{32}, size_t{0}}) {
    const GridSpec grid{{50, 50, 1}, {3, 7, 0}, {20, 20, 1}};
    const GridSpec far{{50, 50, 1}, {3 + 4.5e5, 7 + 5.2e6, 0}, {20, 20, 1}};
    const Grid a = krige(kriger(s, v, {.maxNeighbours = neighbours}), grid);
    const Grid b = krige(kriger(shifted, v, {.maxNeighbours = neighbours}), far);
    for (size_t i = 0; i < a.values.size(); ++i) {
      EXPECT_NEAR(a.values[i], b.values[i], 1e-6 * std::fabs(a.values[i])) << i;
      EXPECT_NEAR(a.variances[i], b.variances[i], 1e-6 * 9.5) << i;
    }
  }
}

TEST(KrigingHardCases, AMillionSamplesInATinyAreaFarFromTheOrigin) {
  // 10^6 samples in a 1 m square at UTM coordinates; nodes inside it and 10 km away (where
  // every brick's candidate ball holds all samples and bricks split down to single nodes).
  PointSet s = randomPoints(1000000, 23, 1.0);
  for (size_t i = 0; i < s.size(); ++i) {
    s.values[i] = std::sin(3 * s.coords[i][0]) + s.coords[i][1];
    s.coords[i][0] += 5.0e5;
    s.coords[i][1] += 5.0e6;
  }
  const Variogram v = model(VariogramType::kExponential, 1e-4, 1, 2);
  const Kriger k = kriger(s, v, {.maxNeighbours = 32});
  EXPECT_EQ(k.sampleCount() + k.mergedSamples(), s.size());
  const GridSpec inside{{20, 20, 1}, {5.0e5 + 0.025, 5.0e6 + 0.025, 0}, {0.05, 0.05, 1}};
  const Grid g = krige(k, inside);
  for (uint32_t y = 0; y < 20; ++y)
    for (uint32_t x = 0; x < 20; ++x) {
      const double truth = std::sin(3 * (0.025 + 0.05 * x)) + 0.025 + 0.05 * y;
      EXPECT_NEAR(g.values[y * 20 + x], truth, 1e-3) << x << "," << y;
    }
  expectSameAsPredict(k, inside, g, 1, 1e-8);
  const GridSpec away{{6, 5, 1}, {5.1e5, 5.0e6, 0}, {100, 100, 1}};
  expectSameAsPredict(k, away, krige(k, away), 1, 1e-8);
}

}  // namespace
}  // namespace voxlink::geostat

namespace voxlink::geostat {
namespace {

TEST(KrigingHardCases, AnisotropyOf1000To1IsIsotropicKrigingInRotatedStretchedSpace) {
  // The range holds along 30 degrees clockwise from +y and is 1000 times shorter across it:
  // the same as isotropic kriging of coordinates rotated onto that direction and stretched.
  const PointSet s = randomPoints(2000, 24, 1000);
  const double angle = 30, ratio = 1e-3;
  const double c = std::cos(angle * M_PI / 180), sn = std::sin(angle * M_PI / 180);
  auto toModel = [&](const Point3& p) {  // any centre will do: distances are the same
    return Point3{p[0] * sn + p[1] * c, (p[0] * c - p[1] * sn) / ratio, 0};
  };
  PointSet stretched = s;
  for (Point3& p : stretched.coords) p = toModel(p);
  const Variogram v = test::model(VariogramType::kExponential, 0.01, 1, 400);
  const GridSpec grid{{25, 20, 1}, {10, 20, 0}, {40, 45, 1}};
  for (size_t neighbours : {size_t{32}, size_t{0}}) {
    const Kriger anis = kriger(
        s, v, {.maxNeighbours = neighbours, .anisotropyAngle = angle, .anisotropyRatio = ratio});
    const Kriger iso = kriger(stretched, v, {.maxNeighbours = neighbours});
    const Grid g = krige(anis, grid);
    EXPECT_GT(g.summary.worstCondition + g.summary.worstConditionBound, 0.0);
    KrigingWorkspace ws;
    for (uint32_t y = 0; y < grid.dims[1]; ++y)
      for (uint32_t x = 0; x < grid.dims[0]; ++x) {
        const size_t at = size_t{y} * grid.dims[0] + x;
        auto p = iso.predict(toModel(grid.node(x, y, 0)), ws);
        ASSERT_TRUE(p) << p.message();
        ASSERT_TRUE(std::isfinite(g.values[at]) && std::isfinite(g.variances[at])) << at;
        EXPECT_NEAR(g.values[at], p->value, 1e-6 * 3) << at;
        EXPECT_NEAR(g.variances[at], p->variance, 1e-6) << at;
      }
  }
  auto bad = Kriger::make(s, v, {.anisotropyRatio = 0});
  ASSERT_FALSE(bad);
  EXPECT_NE(bad.message().find("--anisotropy"), std::string::npos) << bad.message();
}

}  // namespace
}  // namespace voxlink::geostat
