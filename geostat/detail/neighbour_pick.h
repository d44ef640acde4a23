// SPDX-License-Identifier: BSD-3-Clause
// Each node's k nearest among the candidates of its brick (local_kriging.cpp): exactly the set
// and order KdTree::nearest gives (squared distance, then sample index), from the distances to
// the few candidates, ranking only those near the k-th distance.
#pragma once

#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "geostat/detail/kd_tree.h"

namespace voxlink::geostat {

struct PickState {
  std::vector<double> cx, cy, cz;  // the candidates' coordinates, in sample order
  std::vector<double> d2;          // their squared distances to the last node
  std::vector<uint32_t> picked;    // the last node's neighbours (candidate positions, ascending)
  std::vector<std::pair<double, uint32_t>> band;  // (squared distance, candidate) to rank
  std::vector<uint64_t> inside, banded;           // bit masks over the candidates (pickNearest)
  double lastKth = -1;  // the brick's previous node's k-th squared distance (-1: none yet)
  Point3 lastNode{};
};

// The node's k nearest candidates, ascending, in s.picked; false when none is within
// maxDistance.
bool pickNeighbours(const Point3& q, size_t k, double maxDistance, PickState& s);

}  // namespace voxlink::geostat
