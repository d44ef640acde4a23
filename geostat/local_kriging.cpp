// SPDX-License-Identifier: BSD-3-Clause
#include "geostat/detail/local_kriging.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <memory>
#include <mutex>
#include <new>
#include <optional>
#include <utility>

#include "base/parallel_for.h"
#include "geostat/detail/drift.h"
#include "geostat/detail/local_systems.h"
#include "geostat/detail/neighbour_pick.h"
#include "geostat/detail/spd_kernels.h"

namespace voxlink::geostat {
namespace {

constexpr uint32_t kBrickEdge = 16;     // nodes along x and y of a brick before it is split
constexpr uint32_t kSlabDepth = 8;      // slices kriged (and bricks deep) at a time in 3-D
constexpr size_t kCandidateFactor = 4;  // a brick with more than 4 (k + 1) candidates is split
constexpr size_t kBallFactor = 16;      // candidatesFromOneQuery's ball: up to 16 (k + 1)
// Factorizations kept per thread: 512 KiB (~58 systems of 32) stays in cache, where 8 MiB sent
// each new system's writes to memory (docs/kriging-speed-log.md, "Where a 3-D node's time goes");
// against 1 MiB, 2-D Walker Lake took 2 % less CPU (2.6 % more systems) and 3-D the same.
constexpr size_t kCacheBytes = size_t{1} << 19;

struct Box {
  std::array<uint32_t, 3> lo, hi;  // node index ranges [lo, hi)
  uint64_t nodes() const { return uint64_t{hi[0] - lo[0]} * (hi[1] - lo[1]) * (hi[2] - lo[2]); }
};

class BrickSolver {
 public:
  // `values` and `variances` hold rows [y0, y0 + rows) of the slices from z0 on.
  BrickSolver(const Kriger& kriger, const GridSpec& grid, uint32_t z0, uint32_t y0, uint32_t rows,
              double* values, double* variances, double noData, const double* externalDrift)
      : kriger_(kriger),
        systems_(kriger),
        grid_(grid),
        z0_(z0),
        y0_(y0),
        rows_(rows),
        values_(values),
        variances_(variances),
        noData_(noData),
        externalDrift_(externalDrift),
        terms_(kriger.driftBasis().terms()),
        k_(kriger.isGlobal() ? kriger.sampleCount() : kriger.options().maxNeighbours),
        sill_(kriger.variogram().sill()),
        maxDistance_(kriger.options().maxDistance) {}

  Status solve(const Box& box, ThreadState& ts) const {
    // Centre and half-diagonal in model space (a box there only without anisotropy): the
    // farthest corner from the centre bounds every node's distance to it.
    const Point3 a = centred(box.lo[0], box.lo[1], box.lo[2]);
    const Point3 b = centred(box.hi[0] - 1, box.hi[1] - 1, box.hi[2] - 1);
    const Point3 c{0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1]), 0.5 * (a[2] + b[2])};
    double halfDiagonal = 0;
    for (int corner = 0; corner < 8; ++corner) {
      const Point3 p =
          centred(corner & 1 ? box.hi[0] - 1 : box.lo[0], corner & 2 ? box.hi[1] - 1 : box.lo[1],
                  corner & 4 ? box.hi[2] - 1 : box.lo[2]);
      halfDiagonal = std::max(
          halfDiagonal, std::sqrt((p[0] - c[0]) * (p[0] - c[0]) + (p[1] - c[1]) * (p[1] - c[1]) +
                                  (p[2] - c[2]) * (p[2] - c[2])));
    }
    const KdTree& tree = kriger_.tree();
    ts.candidates.clear();
    if (box.nodes() == 1) {  // the node's own neighbours, straight from the tree
      tree.nearest(c, k_, maxDistance_, ts.nearest);
      for (const Neighbour& n : ts.nearest) ts.candidates.push_back(n.index);
    } else if (!candidatesFromOneQuery(c, halfDiagonal, ts)) {
      // The k+1 nearest of any node p lie within d_k+1(c) + |p - c| of p: within
      // d_k+1(c) + 2 h of c. The margin covers rounding in the distances.
      tree.nearest(c, k_ + 1, INFINITY, ts.nearest);
      const double kth = ts.nearest.size() > k_ ? ts.nearest.back().distance : INFINITY;
      ts.pieceKth = kth, ts.pieceCentre = c;
      // A brick far wider than a neighbourhood (samples denser than nodes) would split level
      // by level, a tree query each: cut it at once into pieces of half-diagonal ~0.3 d_k+1.
      if (halfDiagonal > 1.0 * kth) return cut(box, 0.3 * kth, ts);
      const double reach = std::min(kth + 2 * halfDiagonal, maxDistance_ + halfDiagonal);
      if (!tree.within(c, reach * (1 + 1e-9), kCandidateFactor * (k_ + 1), ts.candidates))
        return split(box, ts);
    } else if (ts.candidates.size() > kCandidateFactor * (k_ + 1)) {
      return split(box, ts);  // as the within() query above would have
    }
    std::sort(ts.candidates.begin(), ts.candidates.end());
    systems_.loadCandidates(ts);
    ts.lastPicked.clear();
    ts.lastKth = -1;
    // Back and forth (rows alternate along x, layers along y), so each node is next to the
    // previous one and more nodes keep its neighbour set (Walker Lake: 60.6 % instead of 57.2 %
    // of the nodes; the set rarely survived the jump back to a row's start).
    const uint32_t width = box.hi[0] - box.lo[0], height = box.hi[1] - box.lo[1];
    for (uint32_t z = box.lo[2], row = 0; z < box.hi[2]; ++z)
      for (uint32_t j = 0; j < height; ++j, ++row) {
        const uint32_t y = (z - box.lo[2]) % 2 ? box.hi[1] - 1 - j : box.lo[1] + j;
        for (uint32_t i = 0; i < width; ++i) {
          const uint32_t x = row % 2 ? box.hi[0] - 1 - i : box.lo[0] + i;
          VOXLINK_RETURN_IF_ERROR(solveNode(x, y, z, ts));
        }
      }
    return Status::ok();
  }

  // Factors the queued systems, then solves the nodes that waited for them, in order (two at a
  // time where both have 32 neighbours).
  Status flush(ThreadState& ts) const {
    VOXLINK_RETURN_IF_ERROR(systems_.flush(ts));
    for (size_t k = 0; k < ts.waiting.size(); ++k) {
      const WaitingNode& w = ts.waiting[k];
      if (k + 1 < ts.waiting.size() && w.f->key.size() == 32 &&
          ts.waiting[k + 1].f->key.size() == 32) {
        const WaitingNode& next = ts.waiting[++k];
        VOXLINK_RETURN_IF_ERROR(finishPair({w.node, w.f, &ts.waitingRhs[w.rhs]},
                                           {next.node, next.f, &ts.waitingRhs[next.rhs]}, ts));
      } else {
        VOXLINK_RETURN_IF_ERROR(finishNode(w.node, *w.f, &ts.waitingRhs[w.rhs], ts));
      }
    }
    ts.waiting.clear();
    ts.waitingRhs.clear();
    return Status::ok();
  }

  // Everything of this thread's slab still pending: queued systems and their nodes, and a node
  // waiting for a partner (finishPair).
  Status finishSlab(ThreadState& ts) const {
    VOXLINK_RETURN_IF_ERROR(flush(ts));
    return finishReady(ts);
  }

 private:
  Point3 centred(uint32_t i, uint32_t j, uint32_t k) const {
    return kriger_.modelCoordinates(grid_.node(i, j, k));
  }

  // The candidates of a piece near the previous one (ts.pieceKth at ts.pieceCentre) from one
  // ball query instead of two: d_k+1(c) <= d_k+1(c') + |c - c'| (triangle inequality), so the
  // ball of that radius plus 2 h holds the k+1 nearest of c and every candidate. d_k+1(c) is
  // then the (k+1)-th smallest of the ball's distances (as the tree computes them), and the
  // candidates those within the reach below: the same set, the same bits. False (nothing
  // decided) where it does not apply; the k-nearest query costs ~3.7 times a ball query.
  bool candidatesFromOneQuery(const Point3& c, double halfDiagonal, ThreadState& ts) const {
    if (ts.pieceKth < 0 || !std::isinf(maxDistance_) || !std::isfinite(ts.pieceKth)) return false;
    const double step = std::sqrt((c[0] - ts.pieceCentre[0]) * (c[0] - ts.pieceCentre[0]) +
                                  (c[1] - ts.pieceCentre[1]) * (c[1] - ts.pieceCentre[1]) +
                                  (c[2] - ts.pieceCentre[2]) * (c[2] - ts.pieceCentre[2]));
    if (step > 0.5 * ts.pieceKth) return false;  // a far piece: too wide a ball
    const double ball = (ts.pieceKth + step + 2 * halfDiagonal) * (1 + 1e-6);
    ts.ball.clear();
    ts.ballSquared.clear();
    if (!kriger_.tree().within(c, ball, kBallFactor * (k_ + 1), ts.ball, ts.ballSquared) ||
        ts.ball.size() <= k_)
      return false;
    ts.sortedSquared = ts.ballSquared;
    const auto kthSquared = ts.sortedSquared.begin() + static_cast<long>(k_);
    std::nth_element(ts.sortedSquared.begin(), kthSquared, ts.sortedSquared.end());
    const double kth = std::sqrt(*kthSquared);
    // Pieces are not cut again, and the reach must lie inside the ball.
    const double radius = (kth + 2 * halfDiagonal) * (1 + 1e-9);
    if (halfDiagonal > 1.0 * kth || !(radius <= ball)) return false;
    ts.pieceKth = kth, ts.pieceCentre = c;
    const double radius2 = radius * radius;  // as within() squares it
    for (size_t i = 0; i < ts.ball.size(); ++i)
      if (ts.ballSquared[i] <= radius2) ts.candidates.push_back(ts.ball[i]);
    return true;
  }

  Status cut(const Box& box, double halfDiagonal, ThreadState& ts) const {
    std::array<uint32_t, 3> pieces{1, 1, 1};
    const double edge = 2 * halfDiagonal / std::sqrt(3.0);
    const Point3 origin = centred(box.lo[0], box.lo[1], box.lo[2]);
    for (int a = 0; a < 3; ++a) {
      const uint32_t nodes = box.hi[a] - box.lo[a];
      if (nodes < 2) continue;
      // One node step along axis a, in model space (anisotropy stretches it).
      std::array<uint32_t, 3> next = box.lo;
      ++next[a];
      const Point3 p = centred(next[0], next[1], next[2]);
      const double step = std::sqrt((p[0] - origin[0]) * (p[0] - origin[0]) +
                                    (p[1] - origin[1]) * (p[1] - origin[1]) +
                                    (p[2] - origin[2]) * (p[2] - origin[2]));
      pieces[a] = static_cast<uint32_t>(
          std::clamp(std::ceil(nodes * step / std::max(edge, 1e-300)), 1.0, double(nodes)));
    }
    if (pieces[0] * pieces[1] * pieces[2] == 1) return split(box, ts);  // always progresses
    for (uint32_t pz = 0; pz < pieces[2]; ++pz)
      for (uint32_t py = 0; py < pieces[1]; ++py)
        for (uint32_t px = 0; px < pieces[0]; ++px) {
          Box part = box;
          const std::array<uint32_t, 3> p{px, py, pz};
          for (int a = 0; a < 3; ++a) {
            const uint64_t nodes = box.hi[a] - box.lo[a];
            part.lo[a] = box.lo[a] + static_cast<uint32_t>(nodes * p[a] / pieces[a]);
            part.hi[a] = box.lo[a] + static_cast<uint32_t>(nodes * (p[a] + 1) / pieces[a]);
          }
          VOXLINK_RETURN_IF_ERROR(solve(part, ts));
        }
    return Status::ok();
  }

  Status split(const Box& box, ThreadState& ts) const {
    int axis = -1;
    double widest = 0;
    for (int a = 0; a < 3; ++a) {
      const double extent = (box.hi[a] - box.lo[a] - 1) * grid_.spacing[a];
      if (box.hi[a] - box.lo[a] > 1 && (axis < 0 || extent > widest)) {
        axis = a;
        widest = extent;
      }
    }
    Box first = box, second = box;
    first.hi[axis] = second.lo[axis] = box.lo[axis] + (box.hi[axis] - box.lo[axis]) / 2;
    VOXLINK_RETURN_IF_ERROR(solve(first, ts));
    return solve(second, ts);
  }

  // Picks the node's neighbours and finds or queues its system; the node is solved at once
  // when its system is factored, else once the queue is.
  Status solveNode(uint32_t x, uint32_t y, uint32_t z, ThreadState& ts) const {
    const Point3 q = centred(x, y, z);
    ++ts.summary.nodes;
    if (!pickNeighbours(q, k_, maxDistance_, ts)) {
      const uint64_t at = (uint64_t{z - z0_} * rows_ + y - y0_) * grid_.dims[0] + x;
      // Simple kriging has an answer without data, the known mean and the sill (as predict()).
      const bool simple = kriger_.options().kind == KrigingKind::kSimple;
      values_[at] = simple ? kriger_.options().simpleMean : noData_;
      variances_[at] = simple ? kriger_.variogram().sill() : noData_;
      ++ts.summary.nodesWithoutData;
      return Status::ok();
    }
    const size_t n = ts.picked.size();
    const Factorization* f = nullptr;
    // A set kept by the pick is the previous node's of this brick, whose system is ts.last.
    if (ts.last && (ts.unchanged || ts.picked == ts.lastPicked)) {
      f = ts.last;
    } else {
      ts.key.resize(n);
      for (size_t i = 0; i < n; ++i) ts.key[i] = ts.candidates[ts.picked[i]];
      const uint64_t hash = hashKey(ts.key);
      f = ts.cache.find(hash, ts.key);
      if (!f) {
        // A queued system's slot is not reused before the nodes waiting for it are solved.
        if (ts.cache.victim(hash).pending || !systems_.queueTakes(ts, n))
          VOXLINK_RETURN_IF_ERROR(flush(ts));
        if (ts.ready == &ts.cache.victim(hash)) VOXLINK_RETURN_IF_ERROR(finishReady(ts));
        Factorization& fresh = ts.cache.insert(hash);
        fresh.key = ts.key;
        systems_.queue(ts, fresh);
        f = &fresh;
        ++ts.summary.systemsFactored;
        --ts.summary.systemsReused;  // counted below; this node did not reuse
      }
      ts.last = f;
      ts.lastPicked = ts.picked;
    }
    ++ts.summary.systemsReused;
    if (!f->pending) {
      ts.rhs.resize(n);
      kriger_.variogram().covariancesOfSquared(ts.pickedD2.data(), ts.rhs.data(), n);
      if (n == 32 && !ts.ready) {  // solved with the next such node (finishPair)
        std::swap(ts.rhs, ts.readyRhs);
        ts.ready = f;
        ts.readyNode = {x, y, z};
        return Status::ok();
      }
      if (n == 32) {
        const SolvedNode first{ts.readyNode, ts.ready, ts.readyRhs.data()};
        ts.ready = nullptr;
        return finishPair(first, {{x, y, z}, f, ts.rhs.data()}, ts);
      }
      return finishNode({x, y, z}, *f, ts.rhs.data(), ts);
    }
    const size_t offset = ts.waitingRhs.size();
    ts.waitingRhs.resize(offset + n);
    kriger_.variogram().covariancesOfSquared(ts.pickedD2.data(), &ts.waitingRhs[offset], n);
    ts.waiting.push_back({{x, y, z}, f, offset});
    return Status::ok();
  }

  // A node with its factored system and its covariances (solved in place).
  struct SolvedNode {
    std::array<uint32_t, 3> node;
    const Factorization* f;
    double* rhs;
  };

  Status finishReady(ThreadState& ts) const {
    if (!ts.ready) return Status::ok();
    const Factorization& f = *ts.ready;
    ts.ready = nullptr;
    return finishNode(ts.readyNode, f, ts.readyRhs.data(), ts);
  }

  // Two nodes of 32 neighbours, their solves interleaved (spd::solveNodes32).
  Status finishPair(const SolvedNode& a, const SolvedNode& b, ThreadState& ts) const {
    spd::NodeSolve32 solves[2];
    for (int k = 0; k < 2; ++k) {
      const SolvedNode& s = k == 0 ? a : b;
      solves[k] = {
          s.f->l.data(), s.rhs, s.f->r.data(), terms_ > 0 ? s.f->u.data() : nullptr, 0, 0, 0};
    }
    spd::solveNodes32(solves, 2);
    VOXLINK_RETURN_IF_ERROR(complete(a.node, *a.f, a.rhs, solves[0], ts));
    return complete(b.node, *b.f, b.rhs, solves[1], ts);
  }

  // The node's estimate and variance from its factored system and covariances `rhs` (n).
  Status finishNode(const std::array<uint32_t, 3>& node, const Factorization& f, double* rhs,
                    ThreadState& ts) const {
    const size_t n = f.key.size();
    spd::NodeSolve32 solve{f.l.data(), rhs, f.r.data(), terms_ > 0 ? f.u.data() : nullptr, 0, 0, 0};
    if (n == 32) {
      spd::solveNodes32(&solve, 1);
    } else {
      spd::solveLower(f.l.data(), n, spd::paddedSize(n), rhs);
      solve.yy = spd::dot(rhs, rhs, n);
      solve.ry = spd::dot(f.r.data(), rhs, n);
      if (solve.u) solve.uy = spd::dot(solve.u, rhs, n);
    }
    return complete(node, f, rhs, solve, ts);
  }

  // The rest of a node once y = L^-1 c (in `y`) and its products are known.
  Status complete(const std::array<uint32_t, 3>& node, const Factorization& f, const double* y,
                  const spd::NodeSolve32& solve, ThreadState& ts) const {
    const auto [x, yIndex, z] = node;
    const uint64_t at = (uint64_t{z - z0_} * rows_ + yIndex - y0_) * grid_.dims[0] + x;
    const size_t n = f.key.size();
    double value = kriger_.dataMean() + solve.ry, variance = sill_ - solve.yy;
    if (terms_ > 0) {  // the drift's Lagrange multipliers (drift.h)
      const uint64_t index = (uint64_t{z} * grid_.dims[1] + yIndex) * grid_.dims[0] + x;
      ts.drift.resize(4 * terms_);  // f0, the correction's scratch, the products u_j.y
      const DriftBasis& basis = kriger_.driftBasis();
      basis.at(basis.usesPoint() ? centred(x, yIndex, z) : Point3{},
               externalDrift_ ? externalDrift_[index] : NAN, ts.drift.data());
      double* uy = ts.drift.data() + 3 * terms_;
      uy[0] = solve.uy;
      for (size_t j = 1; j < terms_; ++j) uy[j] = spd::dot(&f.u[j * n], y, n);
      f.drift.correctWithProducts(uy, ts.drift.data(), f.ur.data(), ts.drift.data() + terms_, value,
                                  variance);
      if (f.drift.dropped() > 0) ++ts.summary.driftReducedNodes;
    }
    if (!std::isfinite(value) || !std::isfinite(variance)) {
      const Point3 p = grid_.node(x, yIndex, z);
      return makeError(ErrorCode::kNonFinite, "kriging: non-finite prediction at (", p[0], ", ",
                       p[1], ", ", p[2], ") from ", n, " samples");
    }
    values_[at] = value;
    variances_[at] = std::max(variance, 0.0);  // -1e-16 * sill at a sample is 0
    ts.neighbourSum += static_cast<double>(n);
    if (f.bounded)
      ts.summary.worstConditionBound = std::max(ts.summary.worstConditionBound, f.condition);
    else
      ts.summary.worstCondition = std::max(ts.summary.worstCondition, f.condition);
    if (f.jitter > 0) ++ts.summary.regularizedNodes;
    ts.summary.largestJitter = std::max(ts.summary.largestJitter, f.jitter);
    return Status::ok();
  }

  const Kriger& kriger_;
  LocalSystems systems_;
  const GridSpec& grid_;
  uint32_t z0_, y0_, rows_;
  double* values_;
  double* variances_;
  double noData_;
  const double* externalDrift_;  // per node of the whole grid, or null
  size_t terms_;
  size_t k_;
  double sill_, maxDistance_;
};

}  // namespace

Result<KrigingSummary> krigeGridLocal(const Kriger& kriger, const GridSpec& grid,
                                      const GridPart& part, const NodeRunSink& sink,
                                      const GridKrigingOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  const uint32_t depth =
      grid.dims[2] == 1 ? 1 : std::min(grid.dims[2], std::max(kSlabDepth, options.slicesPerBatch));
  const unsigned threads = base::threadCount(options.threads);
  const size_t n = kriger.isGlobal() ? kriger.sampleCount() : kriger.options().maxNeighbours;
  const size_t cacheEntries =
      kCacheBytes / (8 * (spd::paddedSize(n) * n + (3 + kriger.driftBasis().terms()) * n) + 64);
  std::vector<ThreadState> states;
  states.reserve(threads);
  for (unsigned t = 0; t < threads; ++t) states.emplace_back(cacheEntries);
  const uint32_t bricksX = (grid.dims[0] + kBrickEdge - 1) / kBrickEdge;
  const uint32_t bricksY = (grid.dims[1] + kBrickEdge - 1) / kBrickEdge;
  // The units of a share: rows of bricks, slab by slab; the buffers hold the share's rows.
  const uint64_t slabs = (grid.dims[2] + depth - 1) / depth;
  const uint64_t firstRow = part.firstUnit(slabs * bricksY), endRow = part.endUnit(slabs * bricksY);
  const uint64_t slabNodes = uint64_t{depth} * grid.dims[0] *
                             std::min<uint64_t>(grid.dims[1], (endRow - firstRow) * kBrickEdge);
  // Not zeroed: every node of a slab is written before the sink reads it, and zeroing cost a
  // serial pass over fresh pages (0.7 ms of a 40 ms 2-D solve) that the threads now touch first.
  std::unique_ptr<double[]> values(new (std::nothrow) double[slabNodes]);
  std::unique_ptr<double[]> variances(new (std::nothrow) double[slabNodes]);
  if (!values || !variances)
    return makeError(ErrorCode::kTooLarge, "kriging grid: a slab of ", slabNodes,
                     " nodes does not fit in memory");
  std::mutex failureLock;
  std::optional<Error> failure;
  for (uint64_t slab = firstRow / bricksY; firstRow < endRow && slab * bricksY < endRow; ++slab) {
    const uint32_t z0 = static_cast<uint32_t>(slab * depth);
    const uint32_t count = std::min(depth, grid.dims[2] - z0);
    const uint64_t rowBegin = std::max(firstRow, slab * bricksY) - slab * bricksY;
    const uint64_t rowEnd = std::min(endRow, (slab + 1) * bricksY) - slab * bricksY;
    const uint32_t y0 = static_cast<uint32_t>(rowBegin * kBrickEdge);
    const uint32_t y1 =
        static_cast<uint32_t>(std::min<uint64_t>(rowEnd * kBrickEdge, grid.dims[1]));
    const BrickSolver solver(kriger, grid, z0, y0, y1 - y0, values.get(), variances.get(),
                             options.noData, options.externalDrift);
    // Thread 1 takes bricks from the end backwards, the others from the start: a thread's
    // consecutive bricks are then neighbours whose nodes share neighbour sets, so its cached
    // factorizations carry over (taken alternately, 1-2 % more systems were factored on two
    // threads than on one). A lock per brick of hundreds of nodes costs nothing measurable.
    std::mutex takeLock;
    uint64_t front = rowBegin * bricksX, back = rowEnd * bricksX;
    const auto take = [&](unsigned t, uint64_t& b) {
      std::lock_guard lock(takeLock);
      if (front >= back) return false;
      b = t == 1 ? --back : front++;
      return true;
    };
    std::atomic<bool> stop{false};
    base::runOnThreads(threads, [&](unsigned t) {
      ThreadState& ts = states[t];
      for (uint64_t b; !stop && take(t, b);) {
        const uint32_t bx = static_cast<uint32_t>(b % bricksX) * kBrickEdge;
        const uint32_t by = static_cast<uint32_t>(b / bricksX) * kBrickEdge;
        const Box box{{bx, by, z0},
                      {std::min(bx + kBrickEdge, grid.dims[0]),
                       std::min(by + kBrickEdge, grid.dims[1]), z0 + count}};
        if (Status s = solver.solve(box, ts); !s) {
          std::lock_guard lock(failureLock);
          if (!failure) failure = s.error();
          stop = true;
        }
      }
      // The nodes still waiting belong to this slab. After a failure they are dropped: a failed
      // flush has emptied the queue, and flushing again would solve them on unfactored systems.
      if (stop) return;
      if (Status s = solver.finishSlab(ts); !s) {
        std::lock_guard lock(failureLock);
        if (!failure) failure = s.error();
        stop = true;
      }
    });
    if (failure) return *failure;
    VOXLINK_RETURN_IF_ERROR(forEachRowRun(
        grid.dims, z0, count, y0, y1, [&](uint64_t first, uint64_t nodes, uint64_t offset) {
          return sink(first, nodes, values.get() + offset, variances.get() + offset);
        }));
  }
  KrigingSummary summary;
  for (ThreadState& ts : states) {
    const uint64_t predicted = ts.summary.nodes - ts.summary.nodesWithoutData;
    ts.summary.meanNeighbours = predicted ? ts.neighbourSum / double(predicted) : 0.0;
    summary.add(ts.summary);
  }
  summary.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return summary;
}

}  // namespace voxlink::geostat
