// SPDX-License-Identifier: BSD-3-Clause
// The factorizations local kriging (local_kriging.cpp) keeps per thread: nodes whose
// neighbour sets agree share one, found by the hash of the set.
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include "geostat/detail/drift.h"

namespace voxlink::geostat {

struct Factorization {
  std::vector<uint32_t> key;  // sample indices, ascending
  std::vector<double> l;      // column-major lower factor, leading dimension paddedSize(n)
  std::vector<double> u, r;   // L^-1 F (n x p, column-major) and L^-1 (z - mean)
  std::vector<double> ur;     // U^T r, one per drift term
  DriftSystem drift;          // G = U^T U
  double condition = 0, jitter = 0;
  bool bounded = false;  // condition is the nugget's bound, not an estimate
  bool pending = false;  // queued, not yet factored (local_systems.h)
};

// Factorizations of recently seen neighbour sets, found by the hash of the set: 4-way set
// associative with round-robin replacement, so a lookup or an insert never allocates (in 3-D
// almost every node inserts; a node-based hash map spent a malloc on each).
class FactorizationCache {
 public:
  explicit FactorizationCache(size_t capacity)
      : sets_(std::max<size_t>(capacity, 16) / kWays),
        entries_(sets_ * kWays),
        hashes_(entries_.size()),
        next_(sets_) {}
  Factorization* find(uint64_t hash, const std::vector<uint32_t>& key) {
    const size_t first = (hash % sets_) * kWays;
    for (size_t i = first; i < first + kWays; ++i)
      if (hashes_[i] == hash && entries_[i].key == key) return &entries_[i];
    return nullptr;
  }
  // The slot insert(hash) would reuse next.
  const Factorization& victim(uint64_t hash) const {
    const size_t set = hash % sets_;
    return entries_[set * kWays + next_[set]];
  }
  // A slot for a new set (reusing an old slot's memory).
  Factorization& insert(uint64_t hash) {
    const size_t set = hash % sets_;
    const size_t slot = set * kWays + next_[set];
    next_[set] = static_cast<uint8_t>((next_[set] + 1) % kWays);
    hashes_[slot] = hash;
    entries_[slot].key.clear();  // not a valid entry until factored
    return entries_[slot];
  }

 private:
  static constexpr size_t kWays = 4;
  size_t sets_;
  std::vector<Factorization> entries_;
  std::vector<uint64_t> hashes_;
  std::vector<uint8_t> next_;  // the way each set replaces next
};

// The hash of a neighbour set (sample indices, ascending).
inline uint64_t hashKey(const std::vector<uint32_t>& key) {
  uint64_t h = 1469598103934665603ULL;
  for (uint32_t v : key) h = (h ^ v) * 1099511628211ULL;
  return h ^ (h >> 29);
}

}  // namespace voxlink::geostat
