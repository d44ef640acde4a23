// SPDX-License-Identifier: BSD-3-Clause
// Kriging onto a regular grid, z slice by z slice (x fastest), on all cores, with a summary of
// what the solver had to do: the numbers a user needs to trust (or distrust) the result.
#pragma once

#include <array>
#include <functional>
#include <string>

#include "geostat/detail/grid_part.h"
#include "geostat/detail/kriging.h"

namespace voxlink::geostat {

struct GridSpec {
  std::array<uint32_t, 3> dims{1, 1, 1};
  std::array<double, 3> origin{0, 0, 0};  // coordinates of node (0, 0, 0)
  std::array<double, 3> spacing{1, 1, 1};

  uint64_t sliceNodes() const { return uint64_t{dims[0]} * dims[1]; }
  uint64_t nodeCount() const { return sliceNodes() * dims[2]; }
  Point3 node(uint32_t i, uint32_t j, uint32_t k) const {
    return {origin[0] + i * spacing[0], origin[1] + j * spacing[1], origin[2] + k * spacing[2]};
  }
};

struct KrigingSummary {
  uint64_t nodes = 0;
  uint64_t nodesWithoutData = 0;   // no sample within --max-distance (written as the no-data value)
  uint64_t systemsFactored = 0;    // distinct neighbour sets factored
  uint64_t systemsReused = 0;      // nodes whose neighbour set had been factored already
  uint64_t regularizedNodes = 0;   // nodes whose system needed a diagonal jitter
  uint64_t driftReducedNodes = 0;  // nodes kriged with dependent drift terms dropped (drift.h)
  double worstCondition = 0;       // largest 1-norm condition estimate of any system
  // Systems whose condition a bound (the nugget's, or one from L^-1) keeps below
  // --max-condition are not estimated: how many, and the largest bound.
  uint64_t systemsBounded = 0;
  double worstConditionBound = 0;
  double largestJitter = 0;
  double meanNeighbours = 0;
  // Global kriging with a compactly supported covariance (compact_support.h): nodes solved on
  // their nonzero covariances alone, the sum and the largest of those counts, nodes with none.
  uint64_t sparseNodes = 0, sparseNonzeros = 0, sparseMostNonzeros = 0, sparseEmptyNodes = 0;
  double seconds = 0;

  std::string text() const;  // a few lines for the command's summary
  // Folds in the summary of other nodes (another thread's, another rank's): counts add up,
  // worst cases are the larger, the mean neighbours are weighted by predicted nodes, the time
  // is the longer.
  void add(const KrigingSummary& other);
};

// Receives finished slices [z0, z0 + count): values and variances, x fastest.
using SliceSink = std::function<Status(uint32_t z0, uint32_t count, const double* values,
                                       const double* variances)>;

struct GridKrigingOptions {
  unsigned threads = 0;         // 0: hardware concurrency
  double noData = NAN;          // value (and variance) where ordinary kriging has no sample
  uint32_t slicesPerBatch = 1;  // slices computed before each call of the sink
  // With KrigingOptions::externalDrift: the drift's value at every node of the grid, x fastest
  // (nodeCount() values, finite).
  const double* externalDrift = nullptr;
  // Global kriging: kAuto forms K^-1 and solves each node on its nonzero covariances when the
  // covariance has compact support (spherical) and that costs less; the others force a path
  // (kSparse: every node on its nonzero covariances; for tests and measurements).
  enum class GlobalSolver { kAuto, kTriangular, kSparse };
  GlobalSolver globalSolver = GlobalSolver::kAuto;
};

Result<KrigingSummary> krigeGrid(const Kriger& kriger, const GridSpec& grid, const SliceSink& sink,
                                 const GridKrigingOptions& options = {});

// The nodes of share `part` of the grid (grid_part.h), byte for byte as krigeGrid computes
// them; the summary counts this share's nodes only.
Result<KrigingSummary> krigeGridPart(const Kriger& kriger, const GridSpec& grid,
                                     const GridPart& part, const NodeRunSink& sink,
                                     const GridKrigingOptions& options = {});

}  // namespace voxlink::geostat
