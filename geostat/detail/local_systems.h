// SPDX-License-Identifier: BSD-3-Clause
// The kriging systems of local kriging's bricks (local_kriging.cpp): the candidates' pair
// covariances (evaluated on first use), the gather of a node's system from them, and its
// factorization with the checks of docs/kriging.md's "Numerical safeguards". Systems are queued
// and factored spd::batch::kLanes at a time, one per SIMD lane, with the scalar kernels' bits
// (a lane whose system needs more than the first attempt, jitter or a condition estimate, is
// redone alone by the scalar path, which is what every lane would have run).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "geostat/detail/factorization_cache.h"
#include "geostat/detail/kriging.h"
#include "geostat/detail/neighbour_pick.h"
#include "geostat/detail/spd_batch_kernels.h"
#include "geostat/krige_grid.h"

namespace voxlink::geostat {

// A node whose system was queued: solved once the queue is factored.
struct WaitingNode {
  std::array<uint32_t, 3> node;
  const Factorization* f;
  size_t rhs;  // offset of its covariances in ThreadState::waitingRhs
};

// Aligned to a cache line: the states of two threads sit side by side in one vector, and the
// first one's per-node counters shared a line with the second one's candidate pointers.
struct alignas(64) ThreadState : PickState {
  explicit ThreadState(size_t cacheEntries) : cache(cacheEntries) {}
  std::vector<Neighbour> nearest;
  std::vector<uint32_t> candidates;  // sample indices, ascending
  std::vector<uint32_t> ball;        // a ball query's samples, and their squared distances
  std::vector<double> ballSquared, sortedSquared;
  double pieceKth = -1;  // d_k+1 at the centre of the last piece queried (-1: none yet)
  Point3 pieceCentre{};
  std::vector<double> pair;       // the candidates' covariances (m x m)
  std::vector<uint32_t> missing;  // i + (j << 16) in picked: the pairs to evaluate, distances
  std::vector<double> missingDistance, missingCovariance;
  std::vector<double> rhs, work, drift;
  std::vector<uint32_t> lastPicked, key;
  FactorizationCache cache;
  const Factorization* last = nullptr;  // the previous node's, valid while lastPicked is
  std::array<Factorization*, spd::batch::kLanes> queued{};  // slots; f->key is the set
  size_t queuedCount = 0;
  std::vector<double> compact;  // the queued systems, gathered, spd::batch layout
  std::vector<WaitingNode> waiting;
  std::vector<double> waitingRhs;
  // A node of 32 neighbours whose system is factored, waiting for a second one to be solved
  // with (local_kriging.cpp); null when none.
  const Factorization* ready = nullptr;
  std::array<uint32_t, 3> readyNode{};
  std::vector<double> readyRhs;
  KrigingSummary summary;
  double neighbourSum = 0;
};

class LocalSystems {
 public:
  explicit LocalSystems(const Kriger& kriger);

  // Coordinates of ts.candidates, and their pair covariances marked not yet evaluated.
  void loadCandidates(ThreadState& ts) const;
  // Queues the system of ts.picked (f.key set; f.pending from now on), gathering it from the
  // brick's pair covariances: a flush needs nothing of the brick. The caller flushes first
  // when the queue is full or holds systems of another size (one size per batch).
  void queue(ThreadState& ts, Factorization& f) const;
  bool queueTakes(const ThreadState& ts, size_t n) const {
    return ts.queuedCount < spd::batch::kLanes &&
           (ts.queuedCount == 0 || ts.queued[0]->key.size() == n);
  }
  // Factors every queued system (pending no more); counts the bounded ones in ts.summary.
  Status flush(ThreadState& ts) const;

 private:
  double gather(ThreadState& ts, const std::vector<uint32_t>& key, double jitter, double* a,
                size_t ld) const;
  Status factor(ThreadState& ts, Factorization& f) const;
  void finish(ThreadState& ts, Factorization& f) const;
  void flushLanes(ThreadState& ts, size_t count, std::array<bool, spd::batch::kLanes>& done) const;

  const Kriger& kriger_;
  size_t terms_;
  double sill_, nugget_, maxCondition_;
};

}  // namespace voxlink::geostat
