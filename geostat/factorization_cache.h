// SPDX-License-Identifier: BSD-3-Clause
// The factorizations local kriging (local_kriging.cpp) keeps per thread: nodes whose
// neighbour sets agree share one, found by the hash of the set.
#pragma once

#include <algorithm>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "geostat/drift.h"

namespace voxlink::geostat {

struct Factorization {
  std::vector<uint32_t> key;  // sample indices, ascending
  std::vector<double> l;      // column-major lower factor, leading dimension paddedSize(n)
  std::vector<double> u, r;   // L^-1 F (n x p, column-major) and L^-1 (z - mean)
  std::vector<double> ur;     // U^T r, one per drift term
  DriftSystem drift;          // G = U^T U
  double condition = 0, jitter = 0;
  bool bounded = false;  // condition is the nugget's bound, not an estimate
};

// Factorizations of recently seen neighbour sets, found by the hash of the set.
class FactorizationCache {
 public:
  explicit FactorizationCache(size_t capacity) : capacity_(std::max<size_t>(capacity, 16)) {}
  Factorization* find(uint64_t hash, const std::vector<uint32_t>& key) {
    const auto it = index_.find(hash);
    if (it == index_.end()) return nullptr;
    Factorization& f = entries_[it->second];
    return f.key == key ? &f : nullptr;
  }
  // A slot for a new set (reusing an old slot's memory); forgets everything when full.
  Factorization& insert(uint64_t hash) {
    if (used_ == capacity_) {
      index_.clear();
      used_ = 0;
    }
    if (used_ == entries_.size()) entries_.emplace_back();
    index_[hash] = static_cast<uint32_t>(used_);
    return entries_[used_++];
  }

 private:
  size_t capacity_, used_ = 0;
  std::vector<Factorization> entries_;
  std::unordered_map<uint64_t, uint32_t> index_;
};

// The hash of a neighbour set (sample indices, ascending).
inline uint64_t hashKey(const std::vector<uint32_t>& key) {
  uint64_t h = 1469598103934665603ULL;
  for (uint32_t v : key) h = (h ^ v) * 1099511628211ULL;
  return h ^ (h >> 29);
}

}  // namespace voxlink::geostat
