// SPDX-License-Identifier: BSD-3-Clause
// Shares of a grid (geostat/detail/grid_part.h), the split the MPI ranks use: every share count
// gives, share by share, byte for byte the nodes of one whole-grid run, each node exactly once, for
// local and global kriging (2-D and 3-D, with a drift) and random fields; shares may be empty.
#include <gtest/gtest.h>

#include <cstring>

#include "geostat/grf.h"
#include "geostat/krige_grid.h"
#include "tests/geostat/kriging_test_util.h"

namespace voxlink::geostat {
namespace {

using test::kriger;
using test::model;
using test::randomPoints;

// Values then variances of every node, from `count` shares written where they belong; NaN
// where no share wrote (and a second write of a node fails the test).
std::vector<double> byShares(
    uint32_t count, uint64_t nodes,
    const std::function<Status(const GridPart&, const NodeRunSink&)>& run) {
  std::vector<double> out(2 * nodes, NAN);
  std::vector<uint8_t> seen(nodes, 0);
  for (uint32_t index = 0; index < count; ++index) {
    Status s = run(GridPart{index, count},
                   [&](uint64_t first, uint64_t n, const double* v, const double* var) -> Status {
                     for (uint64_t i = 0; i < n; ++i) {
                       EXPECT_EQ(seen[first + i]++, 0) << "node " << first + i << " twice";
                       out[first + i] = v[i];
                       out[nodes + first + i] = var ? var[i] : 0.0;
                     }
                     return Status::ok();
                   });
    EXPECT_TRUE(s) << s.message();
  }
  return out;
}

void expectSameBytes(const std::vector<double>& a, const std::vector<double>& b, uint32_t count) {
  ASSERT_EQ(a.size(), b.size());
  EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(double)), 0)
      << "shares of " << count << " differ from the whole grid";
}

// The same --threads for every share (global kriging factors on that many BLAS threads, whose
// rounding depends on it; local kriging does not).
void expectSharesMatch(const Kriger& k, const GridSpec& grid, unsigned threads) {
  const std::vector<double> whole = byShares(1, grid.nodeCount(), [&](auto part, auto sink) {
    return krigeGridPart(k, grid, part, sink, {.threads = threads}).status();
  });
  for (uint32_t count : {2u, 3u, 4u, 7u, 64u})
    expectSameBytes(
        byShares(count, grid.nodeCount(),
                 [&](auto part, auto sink) {
                   // Other thread counts too: the split must not depend on them.
                   return krigeGridPart(k, grid, part, sink, {.threads = threads}).status();
                 }),
        whole, count);
}

TEST(GridPart, LocalKriging2dAnd3d) {
  const auto points2 = randomPoints(150, 3);
  expectSharesMatch(
      kriger(points2, model(VariogramType::kSpherical, 0.1, 1, 40), {.maxNeighbours = 12}),
      GridSpec{{53, 47, 1}, {0, 0, 0}, {2, 2, 1}}, 2);
  const auto points3 = randomPoints(300, 4, 100.0, 3);
  KrigingOptions drift{.maxNeighbours = 10};
  drift.drift = DriftKind::kLinear;
  expectSharesMatch(kriger(points3, model(VariogramType::kExponential, 0, 1, 50), drift),
                    GridSpec{{23, 19, 21}, {0, 0, 0}, {4, 5, 4.5}}, 1);
}

TEST(GridPart, GlobalKriging2dAnd3d) {
  const auto points2 = randomPoints(80, 5);
  KrigingOptions quadratic;
  quadratic.drift = DriftKind::kQuadratic;
  expectSharesMatch(kriger(points2, model(VariogramType::kGaussian, 0.01, 1, 40), quadratic),
                    GridSpec{{41, 37, 1}, {0, 0, 0}, {2.5, 2.5, 1}}, 2);
  const auto points3 = randomPoints(60, 6, 100.0, 3);
  expectSharesMatch(kriger(points3, model(VariogramType::kExponential, 0, 1, 50)),
                    GridSpec{{17, 13, 11}, {0, 0, 0}, {6, 7, 9}}, 1);
}

TEST(GridPart, RandomFields) {
  for (const auto& [dims, fft] : {std::pair{std::array<uint32_t, 3>{40, 35, 27}, 48u},
                                  std::pair{std::array<uint32_t, 3>{150, 101, 1}, 48u},
                                  std::pair{std::array<uint32_t, 3>{8, 8, 8}, 0u}}) {
    GrfSpec spec;
    spec.dims = dims;
    spec.model = {VariogramType::kExponential, 0, 1, 6, 0.5};
    spec.fftSize = fft;
    spec.seed = 11;
    const uint64_t voxels = uint64_t{dims[0]} * dims[1] * dims[2];
    auto run = [&](const GridPart& part, const NodeRunSink& sink) {
      return generateGrfPart(spec, part, sink).status();
    };
    const std::vector<double> whole = byShares(1, voxels, run);
    for (uint32_t count : {2u, 3u, 4u, 9u})
      expectSameBytes(byShares(count, voxels, run), whole, count);
  }
}

}  // namespace
}  // namespace voxlink::geostat
