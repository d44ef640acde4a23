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
#include "geostat/detail/compact_support.h"
#include "geostat/detail/drift.h"
#include "geostat/detail/spd_kernels.h"

namespace voxlink::geostat {
namespace {

constexpr size_t kBlockNodes = 256;  // nodes per dtrsm: large enough for level-3 speed
// A node's sparse forms cost about this many times nnz^2 flops of OpenBLAS's dtrmm (one core,
// measured: 0.45-0.54 ns per nnz^2 against 0.034 ns per n^2 flop; docs/kriging-speed-log.md,
// "Global kriging with compact support").
constexpr double kSparsePairFlops = 14;
// Below this many samples the factorization (n^3 / 3 flops: 0.13 s at 2048 on one core) runs
// on one OpenBLAS thread: the outputs are then the same bytes for any --threads.
constexpr size_t kThreadedFactorSamples = 2048;
// Nodes sampled over the whole grid to estimate the sparse path's cost.
constexpr uint64_t kCostSampleNodes = 1024;

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

// What the blocks multiply by: L (a triangular solve per block), L^-1 (worth its n^3 / 3
// flops once the nodes outnumber the samples) or K^-1 (compact support, compact_support.h).
enum class Blocks { kSolve, kTriangularInverse, kInverse };

struct Factor {
  std::vector<double> linv, u, r;  // L, then L^-1 (lower, column-major); L^-1 F, L^-1 (z - m)
  std::vector<double> ur;          // U^T r, one per drift term
  DriftSystem drift;               // G = U^T U
  InverseSystem inverse;           // Blocks::kInverse: K^-1 (then linv is empty)
  double condition = 0, jitter = 0;
  Blocks blocks = Blocks::kSolve;
};

// K^-1 = L^-T L^-1 (LAPACK dpotri, lower triangle, mirrored), alpha = L^-T r, W = L^-T U.
Status invertCovariance(Factor& f, size_t n, double maxCondition) {
  const int ni = static_cast<int>(n);
  InverseSystem& inv = f.inverse;
  inv.n = n;
  inv.alpha = f.r;
  cblas_dtrsv(CblasColMajor, CblasLower, CblasTrans, CblasNonUnit, ni, f.linv.data(), ni,
              inv.alpha.data(), 1);
  inv.w = f.u;
  if (!f.ur.empty())
    cblas_dtrsm(CblasColMajor, CblasLeft, CblasLower, CblasTrans, CblasNonUnit, ni,
                static_cast<int>(f.ur.size()), 1.0, f.linv.data(), ni, inv.w.data(), ni);
  if (LAPACKE_dpotri(LAPACK_COL_MAJOR, 'L', ni, f.linv.data(), ni) != 0)
    return singularSystemError(n, maxCondition);
  inv.kinv = std::move(f.linv);
  f.linv.clear();
  for (size_t j = 0; j < n; ++j)
    for (size_t i = j + 1; i < n; ++i) inv.kinv[i * n + j] = inv.kinv[j * n + i];
  return Status::ok();
}

Result<Factor> factorSamples(const Kriger& kriger, Blocks blocks) {
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
  // (dtrsm; docs/kriging-speed-log.md has the measurement), so the blocks use L^-1 itself.
  f.blocks = blocks;
  if (blocks == Blocks::kInverse) VOXLINK_RETURN_IF_ERROR(invertCovariance(f, n, maxCondition));
  if (blocks == Blocks::kTriangularInverse &&
      LAPACKE_dtrtri(LAPACK_COL_MAJOR, 'L', 'N', ni, f.linv.data(), ni) != 0)
    return singularSystemError(n, maxCondition);
  return f;
}

// Model-space coordinates of node `at` of the batch starting at slice z0, and its drift terms.
Point3 nodeAndDrift(const Kriger& kriger, const GridSpec& grid, const double* externalDrift,
                    uint32_t z0, uint64_t at, double* f0) {
  const uint64_t slice = at / grid.sliceNodes(), inSlice = at % grid.sliceNodes();
  const Point3 node =
      grid.node(static_cast<uint32_t>(inSlice % grid.dims[0]),
                static_cast<uint32_t>(inSlice / grid.dims[0]), z0 + static_cast<uint32_t>(slice));
  const Point3 q = kriger.modelCoordinates(node);
  kriger.driftBasis().at(
      q, externalDrift ? externalDrift[uint64_t{z0} * grid.sliceNodes() + at] : NAN, f0);
  return q;
}

// Per worker thread: the block's covariance columns, drift terms and a node's support.
struct BlockScratch {
  std::vector<double> k, f0;
  NodeSupport support;
  std::vector<size_t> denseNodes;
  uint64_t sparseNodes = 0, sparseNonzeros = 0, sparseMostNonzeros = 0, sparseEmptyNodes = 0;
};

// Estimates and variances of nodes [first, first + count) of the batch starting at slice z0,
// into values[0, count) and variances[0, count), with L or L^-1.
void solveBlock(const Kriger& kriger, const GridSpec& grid, const Factor& f,
                const double* externalDrift, uint32_t z0, uint64_t first, size_t count,
                BlockScratch& s, double* values, double* variances) {
  const size_t terms = f.ur.size();
  s.f0.resize((count + 2) * terms);  // the nodes' drift terms, then a and mu
  const auto& p = kriger.centredSamples();
  const size_t n = p.size();
  const Variogram& v = kriger.variogram();
  for (size_t c = 0; c < count; ++c) {
    const Point3 q =
        nodeAndDrift(kriger, grid, externalDrift, z0, first + c, s.f0.data() + c * terms);
    double* column = &s.k[c * n];
    for (size_t i = 0; i < n; ++i) {
      const double dx = p[i][0] - q[0], dy = p[i][1] - q[1], dz = p[i][2] - q[2];
      column[i] = v.covariance(std::sqrt(dx * dx + dy * dy + dz * dz));
    }
  }
  const int ni = static_cast<int>(n);
  if (f.blocks == Blocks::kTriangularInverse)
    cblas_dtrmm(CblasColMajor, CblasLeft, CblasLower, CblasNoTrans, CblasNonUnit, ni,
                static_cast<int>(count), 1.0, f.linv.data(), ni, s.k.data(), ni);
  else
    cblas_dtrsm(CblasColMajor, CblasLeft, CblasLower, CblasNoTrans, CblasNonUnit, ni,
                static_cast<int>(count), 1.0, f.linv.data(), ni, s.k.data(), ni);
  const double sill = v.sill(), mean = kriger.dataMean();
  for (size_t c = 0; c < count; ++c) {
    const double* y = &s.k[c * n];
    double value = mean + spd::dot(f.r.data(), y, n);
    double variance = sill - spd::dot(y, y, n);
    f.drift.correct(f.u.data(), n, y, s.f0.data() + c * terms, f.ur.data(),
                    s.f0.data() + count * terms, value, variance);
    values[c] = value;
    variances[c] = std::max(variance, 0.0);  // -1e-16 * sill at a sample is 0
  }
}

// A node's estimate and variance from c.alpha, c^T K^-1 c and wc = (K^-1 F)^T c: with
// a = wc - f0 and mu = G^-1 a, the same formulas as DriftSystem::correct.
void finishNode(const Kriger& kriger, const Factor& f, double dotAlpha, double quadratic,
                const double* wc, const double* f0, double* scratch, double& value,
                double& variance) {
  const size_t terms = f.ur.size();
  double* a = scratch;
  double* mu = scratch + terms;
  for (size_t j = 0; j < terms; ++j) mu[j] = a[j] = wc[j] - f0[j];
  f.drift.solve(mu);
  double v = kriger.dataMean() + dotAlpha, var = kriger.variogram().sill() - quadratic;
  for (size_t j = 0; j < terms; ++j) {
    v -= mu[j] * f.ur[j];
    var += mu[j] * a[j];
  }
  value = v;
  variance = std::max(var, 0.0);  // -1e-16 * sill at a sample is 0
}

// The dense nodes s.denseNodes (their covariance columns in s.k's first half) with K^-1: one
// dgemm into the second half, then c.alpha, c.(K^-1 c) and W^T c per node.
void solveDenseWithInverse(const Kriger& kriger, const Factor& f, size_t count, BlockScratch& s,
                           double* values, double* variances) {
  const InverseSystem& inv = f.inverse;
  const size_t n = inv.n, terms = f.ur.size(), dense = s.denseNodes.size();
  if (dense == 0) return;
  const int ni = static_cast<int>(n);
  double* in = s.k.data();
  double* out = s.k.data() + n * (kBlockNodes / 2);
  cblas_dgemm(CblasColMajor, CblasNoTrans, CblasNoTrans, ni, static_cast<int>(dense), ni, 1.0,
              inv.kinv.data(), ni, in, ni, 0.0, out, ni);
  double* wc = s.f0.data() + (count + 2) * terms;
  for (size_t d = 0; d < dense; ++d) {
    const double* c = in + d * n;
    for (size_t j = 0; j < terms; ++j) wc[j] = spd::dot(&inv.w[j * n], c, n);
    const size_t node = s.denseNodes[d];
    finishNode(kriger, f, spd::dot(inv.alpha.data(), c, n), spd::dot(c, out + d * n, n), wc,
               s.f0.data() + node * terms, s.f0.data() + count * terms, values[node],
               variances[node]);
  }
  s.denseNodes.clear();
}

// The same nodes with K^-1 (compact support): a node whose covariance vector has few nonzeros
// is solved on them alone; the others (sparse forms would cost more than their share of a
// dgemm) go through solveDenseWithInverse. `allSparse` forces the sparse forms (tests).
void solveBlockWithInverse(const Kriger& kriger, const GridSpec& grid, const Factor& f,
                           const SupportGatherer& gatherer, bool allSparse,
                           const double* externalDrift, uint32_t z0, uint64_t first, size_t count,
                           BlockScratch& s, double* values, double* variances) {
  const size_t terms = f.ur.size(), n = f.inverse.n;
  s.f0.resize((count + 3) * terms);  // the nodes' drift terms, then a, mu and W^T c
  double* wc = s.f0.data() + (count + 2) * terms;
  const double denseFlops = 2.0 * double(n) * double(n);
  for (size_t c = 0; c < count; ++c) {
    const Point3 q =
        nodeAndDrift(kriger, grid, externalDrift, z0, first + c, s.f0.data() + c * terms);
    gatherer.gather(q, s.support);
    const size_t nnz = s.support.index.size();
    if (!allSparse && kSparsePairFlops * double(nnz) * double(nnz) > denseFlops) {
      double* column = &s.k[s.denseNodes.size() * n];
      std::fill(column, column + n, 0.0);
      for (size_t k = 0; k < nnz; ++k) column[s.support.index[k]] = s.support.covariance[k];
      s.denseNodes.push_back(c);
      if (s.denseNodes.size() == kBlockNodes / 2)
        solveDenseWithInverse(kriger, f, count, s, values, variances);
      continue;
    }
    const SparseForms forms = sparseForms(f.inverse, s.support, terms, wc);
    finishNode(kriger, f, forms.dotAlpha, forms.quadratic, wc, s.f0.data() + c * terms,
               s.f0.data() + count * terms, values[c], variances[c]);
    ++s.sparseNodes;
    s.sparseNonzeros += nnz;
    s.sparseMostNonzeros = std::max<uint64_t>(s.sparseMostNonzeros, nnz);
    s.sparseEmptyNodes += nnz == 0;
  }
  solveDenseWithInverse(kriger, f, count, s, values, variances);
}

// Whether K^-1 and the sparse forms beat L^-1 (or L) over the whole grid, in dgemm flops: the
// inverse costs n^3 / 3 more to form (dpotri against dtrtri), each node min(14 nnz^2, 2 n^2)
// against n^2 (dtrmm; a dtrsm runs at about half its speed). nnz from nodes sampled evenly over
// the whole grid, so every rank and thread count decides alike (byte-identical outputs).
bool inverseIsCheaper(const Kriger& kriger, const GridSpec& grid, const SupportGatherer& gatherer) {
  const double n = double(kriger.sampleCount()), nodes = double(grid.nodeCount());
  const uint64_t stride = std::max<uint64_t>(1, grid.nodeCount() / kCostSampleNodes);
  std::vector<double> f0(kriger.driftBasis().terms() + 1);
  NodeSupport support;
  double sampled = 0, perNode = 0;
  for (uint64_t at = 0; at < grid.nodeCount(); at += stride) {
    gatherer.gather(nodeAndDrift(kriger, grid, nullptr, 0, at, f0.data()), support);
    const double nnz = double(support.index.size());
    perNode += std::min(kSparsePairFlops * nnz * nnz, 2 * n * n);
    ++sampled;
  }
  const double sparse = 2 * n * n * n / 3 + nodes * perNode / sampled;
  const double dense = nodes >= n ? n * n * n / 3 + nodes * n * n : 2 * nodes * n * n;
  return sparse < dense;
}

}  // namespace

uint64_t globalKrigingBytes(size_t samples, unsigned threads) {
  // The factor (or K^-1), a block of covariance columns and a node's support per thread, the
  // vectors of length n (up to 11 drift terms: L^-1 F and K^-1 F; r, alpha) and the sample
  // buckets.
  return 8ull * samples * (samples + (kBlockNodes + 2) * base::threadCount(threads) + 40);
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
  using Solver = GridKrigingOptions::GlobalSolver;
  std::optional<SupportGatherer> gatherer;
  if (options.globalSolver != Solver::kTriangular &&
      std::isfinite(covarianceReach(kriger.variogram())))
    gatherer.emplace(kriger);
  const bool allSparse = gatherer && options.globalSolver == Solver::kSparse;
  Blocks blocks = grid.nodeCount() >= n ? Blocks::kTriangularInverse : Blocks::kSolve;
  if (gatherer && (allSparse || inverseIsCheaper(kriger, grid, *gatherer)))
    blocks = Blocks::kInverse;
  BlasThreads blas;
  blas.set(n >= kThreadedFactorSamples ? threads : 1);
  VOXLINK_ASSIGN_OR_RETURN(const Factor f, factorSamples(kriger, blocks));
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
  KrigingSummary summary;
  std::mutex countsMutex;
  uint64_t ownNodes = 0;
  for (uint64_t batchIndex = firstUnit / batchBlocks;
       firstUnit < endUnit && batchIndex * batchBlocks < endUnit; ++batchIndex) {
    const uint32_t z0 = static_cast<uint32_t>(batchIndex * batch);
    const uint32_t count = std::min(batch, grid.dims[2] - z0);
    const uint64_t nodes = grid.sliceNodes() * count;
    const uint64_t blockBegin =
        std::max(firstUnit, batchIndex * batchBlocks) - batchIndex * batchBlocks;
    const uint64_t blockEnd =
        std::min(endUnit - batchIndex * batchBlocks, (nodes + kBlockNodes - 1) / kBlockNodes);
    const uint64_t begin = blockBegin * kBlockNodes, end = std::min(nodes, blockEnd * kBlockNodes);
    std::atomic<uint64_t> next{blockBegin};
    base::runOnThreads(threads, [&](unsigned) {
      BlockScratch s;
      s.k.resize(n * kBlockNodes);
      for (uint64_t b; (b = next.fetch_add(1)) < blockEnd;) {
        const uint64_t first = b * kBlockNodes,
                       blockNodes = std::min<uint64_t>(kBlockNodes, nodes - first);
        double* v = values.data() + (first - begin);
        double* var = variances.data() + (first - begin);
        if (f.blocks == Blocks::kInverse)
          solveBlockWithInverse(kriger, grid, f, *gatherer, allSparse, options.externalDrift, z0,
                                first, blockNodes, s, v, var);
        else
          solveBlock(kriger, grid, f, options.externalDrift, z0, first, blockNodes, s, v, var);
      }
      const std::lock_guard<std::mutex> lock(countsMutex);
      summary.sparseNodes += s.sparseNodes;
      summary.sparseNonzeros += s.sparseNonzeros;
      summary.sparseMostNonzeros = std::max(summary.sparseMostNonzeros, s.sparseMostNonzeros);
      summary.sparseEmptyNodes += s.sparseEmptyNodes;
    });
    for (uint64_t i = begin; i < end; ++i)
      if (!std::isfinite(values[i - begin]) || !std::isfinite(variances[i - begin]))
        return makeError(ErrorCode::kNonFinite, "kriging: non-finite prediction at node ", i,
                         " of slice ", z0 + i / grid.sliceNodes(), " from ", n, " samples");
    VOXLINK_RETURN_IF_ERROR(
        sink(z0 * grid.sliceNodes() + begin, end - begin, values.data(), variances.data()));
    ownNodes += end - begin;
  }
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
