#include "geostat/krige_grid.h"

#include <algorithm>
#include <sstream>

#include "format/parallel_for.h"
#include "geostat/global_kriging.h"
#include "geostat/local_kriging.h"

namespace voxlink::kriging {

std::string KrigingSummary::text() const {
  std::ostringstream out;
  out.precision(3);
  out << "nodes: " << nodes << " (" << nodesWithoutData << " without a sample in reach)\n"
      << "systems: " << systemsFactored << " factored, " << systemsReused
      << " nodes used a cached factorization; mean neighbours " << meanNeighbours << "\n"
      << "worst condition estimate (1-norm): " << worstCondition;
  if (systemsBounded > 0)
    out << " (" << systemsBounded << " systems not estimated: the nugget bounds their condition by "
        << worstConditionBound << ")";
  out << "\n"
      << "regularized nodes: " << regularizedNodes << " (largest diagonal jitter " << largestJitter
      << ")\n";
  if (driftReducedNodes > 0)
    out << "drift: " << driftReducedNodes
        << " nodes kriged without drift terms that were dependent over their samples\n";
  out << "time: " << seconds << " s\n";
  return out.str();
}

Result<KrigingSummary> krigeGrid(const Kriger& kriger, const GridSpec& grid, const SliceSink& sink,
                                 const GridKrigingOptions& options) {
  VOXLINK_RETURN_IF_ERROR(format::checkThreadCount(options.threads, "kriging grid: threads"));
  for (int a = 0; a < 3; ++a)
    if (grid.dims[a] == 0)
      return makeError(ErrorCode::kInvalidArgument, "kriging grid: axis ", a, " has size 0");
  if (kriger.options().externalDrift && options.externalDrift == nullptr)
    return makeError(ErrorCode::kInvalidArgument,
                     "kriging grid: external drift without its values at the nodes");
  // Global kriging within a search radius has a neighbour set per node: the local path.
  if (kriger.isGlobal() && !std::isfinite(kriger.options().maxDistance))
    return krigeGridGlobal(kriger, grid, sink, options);
  return krigeGridLocal(kriger, grid, sink, options);
}

}  // namespace voxlink::kriging
