// SPDX-License-Identifier: BSD-3-Clause
// Global kriging with a compactly supported covariance (spherical) solves each node on the
// samples within the range, with K^-1 formed once (compact_support.h). It must give what the
// dense path (L^-1, every sample) gives, to rounding: on Walker Lake, and where the number of
// nonzero covariances runs from none (nodes far from the data) to all samples.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>

#include "geostat/detail/compact_support.h"
#include "geostat/detail/sample_buckets.h"
#include "geostat/krige_grid.h"
#include "tests/geostat/kriging_test_util.h"
#include "tests/geostat/walker_lake_data.h"

namespace voxlink::geostat {
namespace {

using Solver = GridKrigingOptions::GlobalSolver;
using test::kriger;
using test::model;
using test::randomPoints;

using Grid = test::KrigedGrid;

Grid krige(const Kriger& k, const GridSpec& grid, Solver solver, unsigned threads = 2,
           const double* externalDrift = nullptr) {
  GridKrigingOptions options;
  options.threads = threads;
  options.globalSolver = solver;
  options.externalDrift = externalDrift;
  return test::krigeInMemory(k, grid, options);
}

// Largest |a - b| relative to max(|b|, scale): relative where |b| is large, relative to the
// data's scale near 0 (a variance of 0 at a sample comes out as +-1e-10 on either path).
double worstRelative(const std::vector<double>& a, const std::vector<double>& b, double scale) {
  double worst = 0;
  for (size_t i = 0; i < a.size(); ++i)
    worst = std::max(worst, std::fabs(a[i] - b[i]) / std::max(std::fabs(b[i]), scale));
  return worst;
}

TEST(SampleBuckets, CandidatesHoldEverySampleWithinReach) {
  for (int dimension : {2, 3})
    for (double reach : {0.01, 7.0, 35.0, 500.0}) {
      const PointSet s = randomPoints(700, 4, 100.0, dimension);
      const SampleBuckets buckets(s.coords, reach);
      std::mt19937_64 rng(9);
      std::uniform_real_distribution<double> u(-60, 160);
      std::vector<uint32_t> found;
      for (int query = 0; query < 300; ++query) {
        // Every 10th query sits on a sample, where distance 0 must be found too.
        const Point3 q = query % 10 == 0 ? s.coords[static_cast<size_t>(query)]
                                         : Point3{u(rng), u(rng), dimension == 3 ? u(rng) : 0};
        found.clear();
        buckets.candidates(q, found);
        std::vector<uint32_t> sorted = found;
        std::sort(sorted.begin(), sorted.end());
        EXPECT_EQ(std::adjacent_find(sorted.begin(), sorted.end()), sorted.end());
        for (size_t i = 0; i < s.size(); ++i) {
          const double dx = s.coords[i][0] - q[0], dy = s.coords[i][1] - q[1],
                       dz = s.coords[i][2] - q[2];
          if (std::sqrt(dx * dx + dy * dy + dz * dz) < reach) {
            EXPECT_TRUE(std::binary_search(sorted.begin(), sorted.end(), uint32_t(i)))
                << "reach " << reach << " query " << query << " sample " << i;
          }
        }
      }
    }
}

TEST(GlobalCompactSupport, OnlySphericalHasAFiniteReach) {
  EXPECT_EQ(covarianceReach(model(VariogramType::kSpherical, 1, 2, 35)), 35);
  for (VariogramType t :
       {VariogramType::kExponential, VariogramType::kGaussian, VariogramType::kMatern})
    EXPECT_TRUE(std::isinf(covarianceReach(model(t, 1, 2, 35, 1.5))));
}

TEST(GlobalCompactSupport, WalkerLakeSparseEqualsDense) {
  VOXLINK_REQUIRE_DATA(test::kWalkerSamples);
  const PointSet s = test::walkerSamples();
  const Variogram v = model(VariogramType::kSpherical, 22144, 70207.9, 35.085);
  const GridSpec grid{{260, 300, 1}, {1, 1, 0}, {1, 1, 1}};
  for (DriftKind drift : {DriftKind::kNone, DriftKind::kLinear}) {
    const Kriger k = kriger(s, v, {.drift = drift});
    const Grid dense = krige(k, grid, Solver::kTriangular);
    const Grid sparse = krige(k, grid, Solver::kSparse);
    const Grid automatic = krige(k, grid, Solver::kAuto);
    EXPECT_EQ(dense.summary.sparseNodes, 0u);
    EXPECT_EQ(sparse.summary.sparseNodes, grid.nodeCount());
    // Walker Lake's range holds a few dozen of the 470 samples: the sparse path is chosen.
    EXPECT_EQ(automatic.summary.sparseNodes, grid.nodeCount());
    EXPECT_LT(automatic.summary.sparseMostNonzeros, 235u);
    for (const Grid* g : {&sparse, &automatic}) {
      EXPECT_LE(worstRelative(g->values, dense.values, 300), 1e-10);
      EXPECT_LE(worstRelative(g->variances, dense.variances, v.sill()), 1e-10);
    }
  }
}

// 300 samples in a 100 x 100 square, range 150, grid from -350 to 450: nodes far outside see
// no sample (nnz 0), nodes in the middle see all 300, so kAuto mixes sparse and dense nodes.
TEST(GlobalCompactSupport, NonzerosFromNoneToAllEqualDense) {
  PointSet s = randomPoints(300, 21);
  std::mt19937_64 rng(5);
  std::normal_distribution<double> noise(0, 1);
  for (size_t i = 0; i < s.size(); ++i) s.drift.push_back(s.coords[i][0] * 0.1 + noise(rng));
  const Variogram v = model(VariogramType::kSpherical, 0.5, 8, 150);
  const GridSpec grid{{41, 37, 1}, {-350, -350, 0}, {20, 22, 1}};
  std::vector<double> nodeDrift(grid.nodeCount());
  for (auto& d : nodeDrift) d = noise(rng) + 5;
  struct Case {
    KrigingOptions options;
    const char* name;
  };
  const Case cases[] = {{{}, "ordinary"},
                        {{.kind = KrigingKind::kSimple, .simpleMean = 10}, "simple"},
                        {{.drift = DriftKind::kLinear}, "linear drift"},
                        {{.drift = DriftKind::kQuadratic, .externalDrift = true}, "quadratic+ext"}};
  for (const Case& c : cases) {
    const Kriger k = kriger(s, v, c.options);
    const double* ext = c.options.externalDrift ? nodeDrift.data() : nullptr;
    const Grid dense = krige(k, grid, Solver::kTriangular, 2, ext);
    const Grid sparse = krige(k, grid, Solver::kSparse, 2, ext);
    const Grid automatic = krige(k, grid, Solver::kAuto, 2, ext);
    EXPECT_EQ(sparse.summary.sparseMostNonzeros, s.size()) << c.name;
    EXPECT_GT(sparse.summary.sparseEmptyNodes, 100u) << c.name;
    EXPECT_GT(automatic.summary.sparseNodes, 0u) << c.name;
    EXPECT_LT(automatic.summary.sparseNodes, grid.nodeCount()) << c.name;  // some went dense
    for (const Grid* g : {&sparse, &automatic}) {
      EXPECT_LE(worstRelative(g->values, dense.values, 3), 1e-10) << c.name;
      EXPECT_LE(worstRelative(g->variances, dense.variances, v.sill()), 1e-10) << c.name;
    }
    // A node with no sample in reach: c = 0, so the estimate is the drift's generalized least
    // squares fit and, for ordinary kriging, the variance sill + 1 / (1^T K^-1 1) > sill.
    if (c.options.kind == KrigingKind::kOrdinary && c.options.drift == DriftKind::kNone) {
      EXPECT_GT(sparse.variances[0], v.sill());
      for (size_t i = 1; i < 10; ++i) {
        EXPECT_DOUBLE_EQ(sparse.values[i], sparse.values[0]);
        EXPECT_DOUBLE_EQ(sparse.variances[i], sparse.variances[0]);
      }
    }
    if (c.options.kind == KrigingKind::kSimple) {
      EXPECT_DOUBLE_EQ(sparse.values[0], 10);
      EXPECT_DOUBLE_EQ(sparse.variances[0], v.sill());
    }
  }
}

// Rows of 512 nodes 0.5 apart cross the samples: more than half a block's nodes see all of
// them and go through the dgemm in several batches; rows far away keep the whole job cheap.
TEST(GlobalCompactSupport, BlocksFullOfDenseNodesEqualDense) {
  const PointSet s = randomPoints(300, 13);
  const Kriger k = kriger(s, model(VariogramType::kSpherical, 0.5, 8, 150));
  const GridSpec grid{{512, 41, 1}, {-78, -2000, 0}, {0.5, 100, 1}};
  const Grid dense = krige(k, grid, Solver::kTriangular);
  const Grid automatic = krige(k, grid, Solver::kAuto);
  EXPECT_GT(automatic.summary.sparseNodes, 0u);
  EXPECT_GT(grid.nodeCount() - automatic.summary.sparseNodes, 300u);
  EXPECT_LE(worstRelative(automatic.values, dense.values, 3), 1e-10);
  EXPECT_LE(worstRelative(automatic.variances, dense.variances, 8.5), 1e-10);
}

TEST(GlobalCompactSupport, SharesAndThreadsWriteTheSameBytes) {
  const PointSet s = randomPoints(500, 8);
  const Kriger k = kriger(s, model(VariogramType::kSpherical, 1, 9, 30));
  const GridSpec grid{{90, 70, 3}, {-20, -10, 0}, {1.5, 1.7, 1}};
  const Grid one = krige(k, grid, Solver::kAuto, 1);
  EXPECT_EQ(one.summary.sparseNodes, grid.nodeCount());
  const Grid two = krige(k, grid, Solver::kAuto, 2);
  // The sparse forms run on the worker threads alone; only the factorization uses OpenBLAS's
  // threads, and at 500 samples it runs on one.
  EXPECT_EQ(std::memcmp(one.values.data(), two.values.data(), one.values.size() * 8), 0);
  std::vector<double> values(grid.nodeCount()), variances(grid.nodeCount());
  for (uint32_t index = 0; index < 3; ++index) {
    auto part = krigeGridPart(
        k, grid, GridPart{index, 3},
        [&](uint64_t first, uint64_t nodes, const double* v, const double* var) -> Status {
          std::copy(v, v + nodes, values.begin() + static_cast<ptrdiff_t>(first));
          std::copy(var, var + nodes, variances.begin() + static_cast<ptrdiff_t>(first));
          return Status::ok();
        },
        {.threads = 2});
    ASSERT_TRUE(part) << part.message();
  }
  EXPECT_EQ(std::memcmp(values.data(), one.values.data(), values.size() * 8), 0);
  EXPECT_EQ(std::memcmp(variances.data(), one.variances.data(), values.size() * 8), 0);
}

}  // namespace
}  // namespace voxlink::geostat
