// SPDX-License-Identifier: BSD-3-Clause
// A k-d tree over 3-D points for the k nearest neighbours of a location within a radius:
// what keeps kriging with 10^4-10^5 samples at O(k^3) per grid node instead of O(n^3).
// nanoflann (libnanoflann-dev) builds and walks the tree; the result sets in kd_tree.cpp keep
// its answers exact and independent of the tree's shape (ties by index), so kriging outputs
// are byte-identical to the hand-written tree it replaced (docs/kriging.md, "Libraries").
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "geostat/point_set.h"

namespace voxlink::geostat {

struct Neighbour {
  uint32_t index;   // into the point list the tree was built from
  double distance;  // Euclidean
};

class KdTree {
 public:
  explicit KdTree(const std::vector<Point3>& points);
  ~KdTree();

  // The up to `k` points nearest to `q` with distance <= maxDistance, nearest first; ties at
  // equal distance are ordered by point index so results never depend on tree shape.
  void nearest(const Point3& q, size_t k, double maxDistance, std::vector<Neighbour>& out) const;
  // Appends the indices of the points within `radius` of q (any order) to `out`; stops and
  // returns false once more than maxCount were found, so a crowded ball costs little.
  bool within(const Point3& q, double radius, size_t maxCount, std::vector<uint32_t>& out) const;
  // The same, also appending each point's squared distance to q as nearest() computes it (the
  // same bits) to `squared`.
  bool within(const Point3& q, double radius, size_t maxCount, std::vector<uint32_t>& out,
              std::vector<double>& squared) const;

 private:
  struct Index;
  std::unique_ptr<Index> index_;
};

}  // namespace voxlink::geostat
