// SPDX-License-Identifier: BSD-3-Clause
// pickNeighbours against a full sort, node after node along grid rows as a brick walks them:
// the same k nearest (distance, then candidate index), including the nodes whose set is kept
// from the previous node without a pick, on lattices where many distances tie.
#include "geostat/detail/neighbour_pick.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

namespace voxlink::geostat {
namespace {

std::vector<uint32_t> bruteForce(const PickState& s, const Point3& q, size_t k, double reach) {
  std::vector<std::pair<double, uint32_t>> all;
  for (uint32_t j = 0; j < s.cx.size(); ++j) {
    const double dx = s.cx[j] - q[0], dy = s.cy[j] - q[1], dz = s.cz[j] - q[2];
    const double d2 = dx * dx + dy * dy + dz * dz;
    if (d2 <= reach * reach) all.emplace_back(d2, j);
  }
  std::sort(all.begin(), all.end());
  if (all.size() > k) all.resize(k);
  std::vector<uint32_t> picked;
  for (const auto& [d2, j] : all) picked.push_back(j);
  std::sort(picked.begin(), picked.end());
  return picked;
}

struct Walk {
  size_t nodes = 0, kept = 0, mismatches = 0;
};

// Every node of a rows x rows brick at `origin` with spacing `step`, in the order local kriging
// walks a brick (the pick state reset at its start).
Walk walkBrick(PickState& s, Point3 origin, double step, int rows, size_t k, double reach) {
  Walk w;
  s.lastKth = -1;
  for (int y = 0; y < rows; ++y)
    for (int x = 0; x < rows; ++x) {
      const Point3 q{origin[0] + x * step, origin[1] + y * step, origin[2]};
      const bool any = pickNeighbours(q, k, reach, s);
      const std::vector<uint32_t> expected = bruteForce(s, q, k, reach);
      EXPECT_EQ(any, !expected.empty());
      if (any && s.picked != expected) ++w.mismatches;
      ++w.nodes;
      w.kept += s.unchanged;
    }
  return w;
}

void fill(PickState& s, const std::vector<Point3>& points) {
  s.cx.clear(), s.cy.clear(), s.cz.clear();
  for (const Point3& p : points) {
    s.cx.push_back(p[0]);
    s.cy.push_back(p[1]);
    s.cz.push_back(p[2]);
  }
}

TEST(NeighbourPick, KeptSetsEqualAFullSortOnAnIntegerLattice) {
  // Candidates on the integer lattice, nodes on it and halfway between: many distances tie
  // at the k-th place, where only the full pick may decide (by index).
  std::vector<Point3> lattice;
  for (int y = -12; y <= 12; ++y)
    for (int x = -12; x <= 12; ++x) lattice.push_back({double(x), double(y), 0});
  PickState s;
  fill(s, lattice);
  Walk total;
  for (const double step : {1.0, 0.5, 0.25})
    for (const size_t k : {size_t{4}, size_t{12}, size_t{32}}) {
      const Walk w = walkBrick(s, {-3, -3, 0}, step, 12, k, INFINITY);
      total.nodes += w.nodes, total.kept += w.kept, total.mismatches += w.mismatches;
    }
  EXPECT_EQ(total.mismatches, 0u);
  EXPECT_GT(total.kept, 0u);  // the kept path ran (and was checked) too
  EXPECT_LT(total.kept, total.nodes);
}

TEST(NeighbourPick, KeptSetsEqualAFullSortOnRandomAndClusteredPoints) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-40, 40);
  size_t kept = 0;
  for (int trial = 0; trial < 20; ++trial) {
    std::vector<Point3> points;
    for (int i = 0; i < 130; ++i) {
      // Every fourth point a near copy of an earlier one, some exact copies (equal distances).
      if (i > 4 && i % 4 == 0) {
        Point3 p = points[rng() % points.size()];
        if (trial % 2) p[0] += 1e-9 * u(rng);
        points.push_back(p);
      } else {
        points.push_back({u(rng), u(rng), trial % 3 == 0 ? u(rng) / 8 : 0.0});
      }
    }
    PickState s;
    fill(s, points);
    const double reach = trial % 4 == 3 ? 25.0 : INFINITY;
    const Walk w = walkBrick(s, {-8, -8, 0}, 1.0, 16, 32, reach);
    EXPECT_EQ(w.mismatches, 0u) << trial;
    kept += w.kept;
  }
  EXPECT_GT(kept, 20u * 256 / 8);  // adjacent nodes share sets: the kept path ran often
}

}  // namespace
}  // namespace voxlink::geostat
