#include "geostat/krige_grid.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <mutex>
#include <optional>
#include <sstream>

#include "format/parallel_for.h"

namespace voxlink::kriging {

std::string KrigingSummary::text() const {
  std::ostringstream out;
  out.precision(3);
  out << "nodes: " << nodes << " (" << nodesWithoutData << " without a sample in reach)\n"
      << "systems: " << systemsFactored << " factored, " << systemsReused
      << " nodes reused the previous neighbour set; mean neighbours " << meanNeighbours << "\n"
      << "worst condition estimate (1-norm): " << worstCondition << "\n"
      << "regularized nodes: " << regularizedNodes << " (largest diagonal jitter " << largestJitter
      << ")\n"
      << "time: " << seconds << " s\n";
  return out.str();
}

Result<KrigingSummary> krigeGrid(const Kriger& kriger, const GridSpec& grid, const SliceSink& sink,
                                 const GridKrigingOptions& options) {
  VOXLINK_RETURN_IF_ERROR(format::checkThreadCount(options.threads, "kriging grid: threads"));
  for (int a = 0; a < 3; ++a)
    if (grid.dims[a] == 0)
      return makeError(ErrorCode::kInvalidArgument, "kriging grid: axis ", a, " has size 0");
  const uint32_t batch = std::max<uint32_t>(1, options.slicesPerBatch);
  const uint64_t batchNodes = grid.sliceNodes() * batch;
  std::vector<double> values, variances;
  try {
    values.resize(batchNodes);
    variances.resize(batchNodes);
  } catch (const std::bad_alloc&) {
    return makeError(ErrorCode::kTooLarge, "kriging grid: a batch of ", batchNodes,
                     " nodes does not fit in memory");
  }
  const unsigned threads = format::threadCount(options.threads);
  KrigingSummary summary;
  const auto start = std::chrono::steady_clock::now();
  double neighbourSum = 0;
  std::mutex merge;
  for (uint32_t z0 = 0; z0 < grid.dims[2]; z0 += batch) {
    const uint32_t count = std::min(batch, grid.dims[2] - z0);
    const uint64_t rows = uint64_t{count} * grid.dims[1];
    std::atomic<uint64_t> nextRow{0};
    std::optional<Error> failure;
    auto work = [&] {
      KrigingWorkspace ws;
      KrigingSummary local;
      double localNeighbours = 0;
      constexpr uint64_t kRowsPerGrab = 4;  // consecutive rows keep neighbour sets cached
      for (;;) {
        const uint64_t r0 = nextRow.fetch_add(kRowsPerGrab);
        if (r0 >= rows) break;
        for (uint64_t r = r0; r < std::min(rows, r0 + kRowsPerGrab); ++r) {
          const uint32_t k = z0 + static_cast<uint32_t>(r / grid.dims[1]);
          const uint32_t j = static_cast<uint32_t>(r % grid.dims[1]);
          for (uint32_t i = 0; i < grid.dims[0]; ++i) {
            const uint64_t at = r * grid.dims[0] + i;
            auto p = kriger.predict(grid.node(i, j, k), ws);
            if (!p) {
              std::lock_guard lock(merge);
              if (!failure) failure = p.error();
              return;
            }
            if (!p->hasData) {
              values[at] = variances[at] = options.noData;
              ++local.nodesWithoutData;
              continue;
            }
            values[at] = p->value;
            variances[at] = p->variance;
            localNeighbours += p->neighbours;
            local.worstCondition = std::max(local.worstCondition, p->condition);
            if (p->jitter > 0) ++local.regularizedNodes;
            local.largestJitter = std::max(local.largestJitter, p->jitter);
          }
        }
      }
      std::lock_guard lock(merge);
      summary.nodesWithoutData += local.nodesWithoutData;
      summary.regularizedNodes += local.regularizedNodes;
      summary.worstCondition = std::max(summary.worstCondition, local.worstCondition);
      summary.largestJitter = std::max(summary.largestJitter, local.largestJitter);
      summary.systemsFactored += ws.systemsFactored;
      summary.systemsReused += ws.systemsReused;
      neighbourSum += localNeighbours;
    };
    format::runOnThreads(threads, [&](unsigned) { work(); });
    if (failure) return *failure;
    VOXLINK_RETURN_IF_ERROR(sink(z0, count, values.data(), variances.data()));
  }
  summary.nodes = grid.nodeCount();
  const uint64_t predicted = summary.nodes - summary.nodesWithoutData;
  summary.meanNeighbours = predicted ? neighbourSum / static_cast<double>(predicted) : 0.0;
  summary.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return summary;
}

}  // namespace voxlink::kriging
