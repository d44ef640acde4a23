// SPDX-License-Identifier: BSD-3-Clause
#include "geostat/krige_grid.h"

#include <algorithm>
#include <sstream>

#include "base/parallel_for.h"
#include "geostat/detail/global_kriging.h"
#include "geostat/detail/local_kriging.h"

namespace voxlink::geostat {

std::string KrigingSummary::text() const {
  std::ostringstream out;
  out.precision(3);
  out << "nodes: " << nodes << " (" << nodesWithoutData << " without a sample in reach)\n"
      << "systems: " << systemsFactored << " factored, " << systemsReused
      << " nodes used a cached factorization; mean neighbours " << meanNeighbours << "\n"
      << "worst condition estimate (1-norm): " << worstCondition;
  if (systemsBounded > 0)
    out << " (" << systemsBounded << " systems not estimated: bounded by " << worstConditionBound
        << ")";
  out << "\n"
      << "regularized nodes: " << regularizedNodes << " (largest diagonal jitter " << largestJitter
      << ")\n";
  if (driftReducedNodes > 0)
    out << "drift: " << driftReducedNodes
        << " nodes kriged without drift terms that were dependent over their samples\n";
  if (sparseNodes > 0)
    out << "compact support: " << sparseNodes << " nodes solved on the samples within the range"
        << " only (mean " << double(sparseNonzeros) / double(sparseNodes) << ", at most "
        << sparseMostNonzeros << "; " << sparseEmptyNodes << " nodes with none)\n";
  out << "time: " << seconds << " s\n";
  return out.str();
}

void KrigingSummary::add(const KrigingSummary& other) {
  const uint64_t predicted = nodes - nodesWithoutData;
  const uint64_t otherPredicted = other.nodes - other.nodesWithoutData;
  const uint64_t bothPredicted = predicted + otherPredicted;
  meanNeighbours =
      bothPredicted
          ? (meanNeighbours * double(predicted) + other.meanNeighbours * double(otherPredicted)) /
                double(bothPredicted)
          : 0.0;
  nodes += other.nodes;
  nodesWithoutData += other.nodesWithoutData;
  systemsFactored += other.systemsFactored;
  systemsReused += other.systemsReused;
  regularizedNodes += other.regularizedNodes;
  driftReducedNodes += other.driftReducedNodes;
  systemsBounded += other.systemsBounded;
  sparseNodes += other.sparseNodes;
  sparseNonzeros += other.sparseNonzeros;
  sparseMostNonzeros = std::max(sparseMostNonzeros, other.sparseMostNonzeros);
  sparseEmptyNodes += other.sparseEmptyNodes;
  worstCondition = std::max(worstCondition, other.worstCondition);
  worstConditionBound = std::max(worstConditionBound, other.worstConditionBound);
  largestJitter = std::max(largestJitter, other.largestJitter);
  seconds = std::max(seconds, other.seconds);
}

Result<KrigingSummary> krigeGrid(const Kriger& kriger, const GridSpec& grid, const SliceSink& sink,
                                 const GridKrigingOptions& options) {
  // One share of one: runs of whole slices, in order.
  const uint64_t sliceNodes = grid.sliceNodes();
  return krigeGridPart(
      kriger, grid, GridPart{},
      [&](uint64_t first, uint64_t nodes, const double* values, const double* variances) {
        return sink(static_cast<uint32_t>(first / sliceNodes),
                    static_cast<uint32_t>(nodes / sliceNodes), values, variances);
      },
      options);
}

Result<KrigingSummary> krigeGridPart(const Kriger& kriger, const GridSpec& grid,
                                     const GridPart& part, const NodeRunSink& sink,
                                     const GridKrigingOptions& options) {
  if (part.count == 0 || part.index >= part.count)
    return makeError(ErrorCode::kInvalidArgument, "kriging grid: share ", part.index, " of ",
                     part.count);
  VOXLINK_RETURN_IF_ERROR(base::checkThreadCount(options.threads, "kriging grid: threads"));
  for (int a = 0; a < 3; ++a)
    if (grid.dims[a] == 0)
      return makeError(ErrorCode::kInvalidArgument, "kriging grid: axis ", a, " has size 0");
  if (kriger.options().externalDrift && options.externalDrift == nullptr)
    return makeError(ErrorCode::kInvalidArgument,
                     "kriging grid: external drift without its values at the nodes");
  // Global kriging within a search radius has a neighbour set per node: the local path.
  if (kriger.isGlobal() && !std::isfinite(kriger.options().maxDistance))
    return krigeGridGlobal(kriger, grid, part, sink, options);
  return krigeGridLocal(kriger, grid, part, sink, options);
}

}  // namespace voxlink::geostat
