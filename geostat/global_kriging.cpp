// SPDX-License-Identifier: BSD-3-Clause
#include "geostat/detail/global_kriging.h"

#include <cblas.h>
#include <lapacke.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <mutex>
#include <optional>

#include "base/parallel_for.h"
#include "base/process_memory.h"
#include "geostat/detail/drift.h"
#include "geostat/detail/spd_kernels.h"

namespace voxlink::geostat {
namespace {

constexpr size_t kBlockNodes = 256;  // nodes per dtrsm: large enough for level-3 speed

// OpenBLAS's own thread count, restored when the grid is done: it threads the factorization
// and stays at one thread inside the grid's workers so the two never oversubscribe the cores.
class BlasThreads {
 public:
  BlasThreads() : saved_(openblas_get_num_threads()) {}
  ~BlasThreads() { openblas_set_num_threads(saved_); }
  void set(unsigned threads) { openblas_set_num_threads(static_cast<int>(threads)); }

 private:
  int saved_;
};

// Lower triangle of the samples' covariance matrix plus jitter on the diagonal, column-major.
double fillCovariance(const Kriger& kriger, double jitter, std::vector<double>& a) {
  const auto& p = kriger.centredSamples();
  const size_t n = p.size();
  const Variogram& v = kriger.variogram();
  std::vector<double> columnSum(n, 0.0);
  for (size_t j = 0; j < n; ++j) {
    double* cj = &a[j * n];
    cj[j] = v.sill() + jitter;
    columnSum[j] += cj[j];
    for (size_t i = j + 1; i < n; ++i) {
      const double dx = p[i][0] - p[j][0], dy = p[i][1] - p[j][1], dz = p[i][2] - p[j][2];
      const double c = v.covariance(std::max(std::sqrt(dx * dx + dy * dy + dz * dz), 1e-300));
      cj[i] = c;
      columnSum[j] += std::fabs(c);
      columnSum[i] += std::fabs(c);
    }
  }
  return *std::max_element(columnSum.begin(), columnSum.end());
}

struct Factor {
  std::vector<double> linv, u, r;  // L, then L^-1 (lower, column-major); L^-1 F, L^-1 (z - m)
  std::vector<double> ur;          // U^T r, one per drift term
  DriftSystem drift;               // G = U^T U
  double condition = 0, jitter = 0;
  bool inverted = false;  // linv holds L^-1 (else L)
};

// `invert`: replace L by L^-1 for the blocks (worth its n^3 / 3 flops once the nodes outnumber
// the samples).
Result<Factor> factorSamples(const Kriger& kriger, bool invert) {
  const size_t n = kriger.sampleCount();
  const int ni = static_cast<int>(n);
  const double sill = kriger.variogram().sill(), maxCondition = kriger.options().maxCondition;
  Factor f;
  try {
    f.linv.resize(n * n);
  } catch (const std::bad_alloc&) {
    return makeError(ErrorCode::kTooLarge, "kriging: the ", n, " x ", n,
                     " covariance matrix does not fit in memory; use --neighbours 16..256");
  }
  for (double jitter = 0;;) {
    const double norm1 = fillCovariance(kriger, jitter, f.linv);
    if (LAPACKE_dpotrf(LAPACK_COL_MAJOR, 'L', ni, f.linv.data(), ni) == 0) {
      double rcond = 0;
      if (LAPACKE_dpocon(LAPACK_COL_MAJOR, 'L', ni, f.linv.data(), ni, norm1, &rcond) == 0 &&
          rcond > 0 && 1.0 / rcond <= maxCondition) {
        f.condition = 1.0 / rcond;
        f.jitter = jitter;
        break;
      }
    }
    jitter = jitter == 0 ? kFirstJitter * sill : jitter * 10;
    if (jitter > kLastJitter * sill * 1.0000001) return singularSystemError(n, maxCondition);
  }
  const size_t p = kriger.driftBasis().terms();
  f.u.resize(n * p);
  std::vector<double> terms(p);
  for (size_t i = 0; i < n; ++i) {
    kriger.sampleDriftTerms(i, terms.data());
    for (size_t j = 0; j < p; ++j) f.u[j * n + i] = terms[j];
  }
  f.r.resize(n);
  for (size_t i = 0; i < n; ++i) f.r[i] = kriger.values()[i] - kriger.dataMean();
  cblas_dtrsv(CblasColMajor, CblasLower, CblasNoTrans, CblasNonUnit, ni, f.linv.data(), ni,
              f.r.data(), 1);
  if (p > 0)
    cblas_dtrsm(CblasColMajor, CblasLeft, CblasLower, CblasNoTrans, CblasNonUnit, ni,
                static_cast<int>(p), 1.0, f.linv.data(), ni, f.u.data(), ni);
  f.drift.factor(f.u.data(), n, n, p);
  f.ur.resize(p);
  for (size_t j = 0; j < p; ++j) f.ur[j] = spd::dot(&f.u[j * n], f.r.data(), n);
  // OpenBLAS multiplies by a triangle (dtrmm) nearly three times as fast as it solves with one
  // (dtrsm; docs/kriging.md has the measurement), so the blocks use L^-1 itself.
  f.inverted = invert;
  if (invert && LAPACKE_dtrtri(LAPACK_COL_MAJOR, 'L', 'N', ni, f.linv.data(), ni) != 0)
    return singularSystemError(n, maxCondition);
  return f;
}

// Estimates and variances of nodes [first, first + count) of the batch starting at slice z0,
// into values[0, count) and variances[0, count).
void solveBlock(const Kriger& kriger, const GridSpec& grid, const Factor& f,
                const double* externalDrift, uint32_t z0, uint64_t first, size_t count,
                std::vector<double>& k, std::vector<double>& f0, double* values,
                double* variances) {
  const size_t terms = f.ur.size();
  f0.resize((count + 2) * terms);  // the nodes' drift terms, then a and mu
  const auto& p = kriger.centredSamples();
  const size_t n = p.size();
  const Variogram& v = kriger.variogram();
  for (size_t c = 0; c < count; ++c) {
    const uint64_t at = first + c;
    const uint64_t slice = at / grid.sliceNodes(), inSlice = at % grid.sliceNodes();
    const Point3 node =
        grid.node(static_cast<uint32_t>(inSlice % grid.dims[0]),
                  static_cast<uint32_t>(inSlice / grid.dims[0]), z0 + static_cast<uint32_t>(slice));
    const Point3 q = kriger.modelCoordinates(node);
    kriger.driftBasis().at(
        q, externalDrift ? externalDrift[uint64_t{z0} * grid.sliceNodes() + at] : NAN,
        &f0[c * terms]);
    double* column = &k[c * n];
    for (size_t i = 0; i < n; ++i) {
      const double dx = p[i][0] - q[0], dy = p[i][1] - q[1], dz = p[i][2] - q[2];
      column[i] = v.covariance(std::sqrt(dx * dx + dy * dy + dz * dz));
    }
  }
  const int ni = static_cast<int>(n);
  if (f.inverted)
    cblas_dtrmm(CblasColMajor, CblasLeft, CblasLower, CblasNoTrans, CblasNonUnit, ni,
                static_cast<int>(count), 1.0, f.linv.data(), ni, k.data(), ni);
  else
    cblas_dtrsm(CblasColMajor, CblasLeft, CblasLower, CblasNoTrans, CblasNonUnit, ni,
                static_cast<int>(count), 1.0, f.linv.data(), ni, k.data(), ni);
  const double sill = v.sill(), mean = kriger.dataMean();
  for (size_t c = 0; c < count; ++c) {
    const double* y = &k[c * n];
    double value = mean + spd::dot(f.r.data(), y, n);
    double variance = sill - spd::dot(y, y, n);
    f.drift.correct(f.u.data(), n, y, &f0[c * terms], f.ur.data(), &f0[count * terms], value,
                    variance);
    values[c] = value;
    variances[c] = std::max(variance, 0.0);  // -1e-16 * sill at a sample is 0
  }
}

}  // namespace

uint64_t globalKrigingBytes(size_t samples, unsigned threads) {
  return 8ull * samples * (samples + kBlockNodes * base::threadCount(threads) + 14);
}

Result<KrigingSummary> krigeGridGlobal(const Kriger& kriger, const GridSpec& grid,
                                       const GridPart& part, const NodeRunSink& sink,
                                       const GridKrigingOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  const unsigned threads = base::threadCount(options.threads);
  const size_t n = kriger.sampleCount();
  const uint64_t need = globalKrigingBytes(n, threads), have = base::memoryForThisProcess();
  if (need > have)
    return makeError(ErrorCode::kTooLarge, "kriging: global kriging of ", n, " samples needs ",
                     need >> 20, " MiB (the ", n, " x ", n, " factor), this process may use ",
                     have >> 20, " MiB; use --neighbours 16..256");
  BlasThreads blas;
  blas.set(threads);
  VOXLINK_ASSIGN_OR_RETURN(const Factor f, factorSamples(kriger, grid.nodeCount() >= n));
  blas.set(1);

  // The units of a share: the blocks of every batch of slices, numbered in file order; the
  // buffers hold the share's nodes of one batch.
  const uint32_t batch = std::max<uint32_t>(1, options.slicesPerBatch);
  const uint64_t batchNodes = grid.sliceNodes() * batch;
  const uint64_t batchBlocks = (batchNodes + kBlockNodes - 1) / kBlockNodes;
  const uint64_t lastNodes =
      grid.sliceNodes() * (grid.dims[2] - (grid.dims[2] - 1) / batch * batch);
  const uint64_t units =
      (grid.dims[2] - 1) / batch * batchBlocks + (lastNodes + kBlockNodes - 1) / kBlockNodes;
  const uint64_t firstUnit = part.firstUnit(units), endUnit = part.endUnit(units);
  const uint64_t bufferNodes = std::min(batchNodes, (endUnit - firstUnit) * kBlockNodes);
  std::vector<double> values, variances;
  try {
    values.resize(bufferNodes), variances.resize(bufferNodes);
  } catch (const std::bad_alloc&) {
    return makeError(ErrorCode::kTooLarge, "kriging grid: a batch of ", bufferNodes,
                     " nodes does not fit in memory");
  }
  uint64_t ownNodes = 0;
  for (uint64_t batchIndex = firstUnit / batchBlocks;
       firstUnit < endUnit && batchIndex * batchBlocks < endUnit; ++batchIndex) {
    const uint32_t z0 = static_cast<uint32_t>(batchIndex * batch);
    const uint32_t count = std::min(batch, grid.dims[2] - z0);
    const uint64_t nodes = grid.sliceNodes() * count;
    const uint64_t blockBegin =
        std::max(firstUnit, batchIndex * batchBlocks) - batchIndex * batchBlocks;
    const uint64_t blocks =
        std::min(endUnit - batchIndex * batchBlocks, (nodes + kBlockNodes - 1) / kBlockNodes);
    const uint64_t begin = blockBegin * kBlockNodes, end = std::min(nodes, blocks * kBlockNodes);
    std::atomic<uint64_t> next{blockBegin};
    base::runOnThreads(threads, [&](unsigned) {
      std::vector<double> k(n * kBlockNodes), drift;
      for (uint64_t b; (b = next.fetch_add(1)) < blocks;) {
        const uint64_t first = b * kBlockNodes;
        solveBlock(kriger, grid, f, options.externalDrift, z0, first,
                   std::min<uint64_t>(kBlockNodes, nodes - first), k, drift,
                   values.data() + (first - begin), variances.data() + (first - begin));
      }
    });
    for (uint64_t i = begin; i < end; ++i)
      if (!std::isfinite(values[i - begin]) || !std::isfinite(variances[i - begin]))
        return makeError(ErrorCode::kNonFinite, "kriging: non-finite prediction at node ", i,
                         " of slice ", z0 + i / grid.sliceNodes(), " from ", n, " samples");
    VOXLINK_RETURN_IF_ERROR(
        sink(z0 * grid.sliceNodes() + begin, end - begin, values.data(), variances.data()));
    ownNodes += end - begin;
  }
  KrigingSummary summary;
  summary.nodes = ownNodes;
  summary.systemsFactored = 1;  // on every rank of a shared grid
  summary.systemsReused = summary.nodes ? summary.nodes - 1 : 0;
  summary.worstCondition = f.condition;
  summary.regularizedNodes = f.jitter > 0 ? summary.nodes : 0;
  summary.largestJitter = f.jitter;
  summary.driftReducedNodes = f.drift.dropped() > 0 ? summary.nodes : 0;
  summary.meanNeighbours = static_cast<double>(n);
  summary.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return summary;
}

}  // namespace voxlink::geostat
