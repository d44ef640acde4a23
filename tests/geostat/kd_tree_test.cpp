// SPDX-License-Identifier: BSD-3-Clause
#include "geostat/detail/kd_tree.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

namespace voxlink::geostat {
namespace {

std::vector<Neighbour> bruteForce(const std::vector<Point3>& pts, const Point3& q, size_t k,
                                  double maxDistance) {
  std::vector<Neighbour> all;
  for (uint32_t i = 0; i < pts.size(); ++i) {
    const double d = std::sqrt((pts[i][0] - q[0]) * (pts[i][0] - q[0]) +
                               (pts[i][1] - q[1]) * (pts[i][1] - q[1]) +
                               (pts[i][2] - q[2]) * (pts[i][2] - q[2]));
    if (d <= maxDistance) all.push_back({i, d});
  }
  std::sort(all.begin(), all.end(), [](const Neighbour& a, const Neighbour& b) {
    return a.distance < b.distance || (a.distance == b.distance && a.index < b.index);
  });
  if (all.size() > k) all.resize(k);
  return all;
}

TEST(KdTree, MatchesBruteForceIncludingTiesOnAnIntegerLattice) {
  std::mt19937 rng(5);
  std::uniform_int_distribution<int> coord(0, 20);  // many equal distances
  std::vector<Point3> pts(3000);
  for (auto& p : pts) p = {double(coord(rng)), double(coord(rng)), double(coord(rng) % 3)};
  const KdTree tree(pts);
  std::vector<Neighbour> got;
  for (int t = 0; t < 300; ++t) {
    const Point3 q{double(coord(rng)) + 0.5 * (t % 2), double(coord(rng)), 1.0};
    for (size_t k : {1, 8, 33}) {
      for (double r : {double(INFINITY), 3.0}) {
        tree.nearest(q, k, r, got);
        const auto want = bruteForce(pts, q, k, r);
        ASSERT_EQ(got.size(), want.size());
        for (size_t i = 0; i < got.size(); ++i) {
          EXPECT_EQ(got[i].index, want[i].index) << "query " << t << " k " << k << " rank " << i;
          EXPECT_DOUBLE_EQ(got[i].distance, want[i].distance);
        }
      }
    }
  }
}

// The k nearest by squared distance (p - q, as the tree computes it; the square roots of two
// different squares can be equal), then index.
std::vector<uint32_t> bruteForceSquared(const std::vector<Point3>& pts, const Point3& q, size_t k) {
  std::vector<std::pair<double, uint32_t>> all;
  for (uint32_t i = 0; i < pts.size(); ++i) {
    const double dx = pts[i][0] - q[0], dy = pts[i][1] - q[1], dz = pts[i][2] - q[2];
    all.push_back({dx * dx + dy * dy + dz * dz, i});
  }
  std::sort(all.begin(), all.end());
  std::vector<uint32_t> out;
  for (size_t i = 0; i < std::min(k, all.size()); ++i) out.push_back(all[i].second);
  return out;
}

// Coordinates in steps of 0.1 (not exact in binary): the tree's per-axis bounds round, and
// points exactly at the k-th distance must still be found and ordered by index.
TEST(KdTree, MatchesBruteForceWithTiesOnAnInexactLattice) {
  std::mt19937 rng(11);
  std::uniform_int_distribution<int> coord(-15, 15);
  std::vector<Point3> pts(4000);
  for (auto& p : pts) p = {0.1 * coord(rng), 0.1 * coord(rng), 0.1 * (coord(rng) % 4)};
  const KdTree tree(pts);
  std::vector<Neighbour> got;
  for (int t = 0; t < 300; ++t) {
    const Point3 q{0.1 * coord(rng), 0.1 * coord(rng), 0.1 * (t % 3)};
    for (size_t k : {5, 16, 64}) {
      tree.nearest(q, k, INFINITY, got);
      const auto want = bruteForceSquared(pts, q, k);
      ASSERT_EQ(got.size(), want.size());
      for (size_t i = 0; i < got.size(); ++i)
        ASSERT_EQ(got[i].index, want[i]) << "query " << t << " k " << k << " rank " << i;
    }
  }
}

TEST(KdTree, WithinFindsThePointsOnTheSphereAndStopsPastMaxCount) {
  std::mt19937 rng(3);
  std::uniform_int_distribution<int> coord(0, 12);
  std::vector<Point3> pts(2000);
  for (auto& p : pts) p = {double(coord(rng)), double(coord(rng)), double(coord(rng))};
  const KdTree tree(pts);
  for (int t = 0; t < 200; ++t) {
    const Point3 q{double(coord(rng)), double(coord(rng)), double(coord(rng))};
    const double radius = 1 + t % 4;  // lattice points lie exactly on these spheres
    std::vector<uint32_t> want;
    for (uint32_t i = 0; i < pts.size(); ++i) {
      const double dx = pts[i][0] - q[0], dy = pts[i][1] - q[1], dz = pts[i][2] - q[2];
      if (dx * dx + dy * dy + dz * dz <= radius * radius) want.push_back(i);
    }
    std::vector<uint32_t> got;
    ASSERT_TRUE(tree.within(q, radius, want.size(), got));
    std::sort(got.begin(), got.end());
    ASSERT_EQ(got, want) << "query " << t;
    if (want.empty()) continue;
    got.clear();
    EXPECT_FALSE(tree.within(q, radius, want.size() - 1, got)) << "query " << t;
  }
}

TEST(KdTree, HandlesCoincidentPointsAndEmptyInput) {
  std::vector<Point3> same(100, Point3{1, 2, 3});
  const KdTree tree(same);
  std::vector<Neighbour> got;
  tree.nearest({1, 2, 3}, 5, INFINITY, got);
  ASSERT_EQ(got.size(), 5u);
  for (uint32_t i = 0; i < 5; ++i) EXPECT_EQ(got[i].index, i);
  const KdTree empty(std::vector<Point3>{});
  empty.nearest({0, 0, 0}, 3, INFINITY, got);
  EXPECT_TRUE(got.empty());
}

}  // namespace
}  // namespace voxlink::geostat
