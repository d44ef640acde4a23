#include "geostat/kd_tree.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

namespace voxlink::kriging {
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
}  // namespace voxlink::kriging
