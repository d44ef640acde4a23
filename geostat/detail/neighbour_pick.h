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
  std::vector<double> pickedD2;    // their squared distances, in the same order
  std::vector<std::pair<double, uint32_t>> band;  // (squared distance, candidate) to rank
  std::vector<uint64_t> inside, banded;           // bit masks over the candidates (pickNearest)
  // The brick's previous node's k-th squared distance (-1: none yet, and s.picked is not the
  // brick's: the caller sets it at each brick's start).
  double lastKth = -1;
  Point3 lastNode{};
  bool unchanged = false;  // s.picked is the previous node's set, kept by proof
};

// The node's k nearest candidates, ascending, in s.picked (their squared distances in
// s.pickedD2); false when none is within maxDistance. s.unchanged when the previous node's k
// nearest were kept without a pick.
bool pickNeighbours(const Point3& q, size_t k, double maxDistance, PickState& s);

}  // namespace voxlink::geostat
