// SPDX-License-Identifier: BSD-3-Clause
// The fast triangle/voxel test against the plain 13-axis SAT, and the tie rule.
#include "geometry/detail/triangle_box_overlap.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

namespace voxlink::geometry {
namespace {

// Signed separation of triangle and voxel box over the 13 SAT axes (largest gap along a unit
// axis; <= 0 means overlap, about 0 means they only touch). For judging disagreements.
double separation(const Vec3d& a, const Vec3d& b, const Vec3d& c, int64_t i, int64_t j, int64_t k) {
  const Vec3d centre = {i + 0.5, j + 0.5, k + 0.5};
  Vec3d v[3];
  for (int t = 0; t < 3; ++t)
    for (int x = 0; x < 3; ++x) v[t][x] = (t == 0 ? a : t == 1 ? b : c)[x] - centre[x];
  std::vector<Vec3d> axes = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  const Vec3d e[3] = {{v[1][0] - v[0][0], v[1][1] - v[0][1], v[1][2] - v[0][2]},
                      {v[2][0] - v[1][0], v[2][1] - v[1][1], v[2][2] - v[1][2]},
                      {v[0][0] - v[2][0], v[0][1] - v[2][1], v[0][2] - v[2][2]}};
  auto cross = [](const Vec3d& p, const Vec3d& q) {
    return Vec3d{p[1] * q[2] - p[2] * q[1], p[2] * q[0] - p[0] * q[2], p[0] * q[1] - p[1] * q[0]};
  };
  for (const Vec3d& edge : e)
    for (int u = 0; u < 3; ++u) axes.push_back(cross(edge, axes[u]));
  axes.push_back(cross(e[0], e[1]));
  double worst = -1e300;
  for (const Vec3d& axis : axes) {
    const double length = std::sqrt(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]);
    if (length == 0.0) continue;
    double lo = 1e300, hi = -1e300;
    for (const Vec3d& p : v) {
      const double d = (axis[0] * p[0] + axis[1] * p[1] + axis[2] * p[2]) / length;
      lo = std::min(lo, d);
      hi = std::max(hi, d);
    }
    const double r = 0.5 * (std::abs(axis[0]) + std::abs(axis[1]) + std::abs(axis[2])) / length;
    worst = std::max({worst, lo - r, -r - hi});
  }
  return worst;
}

TEST(TriangleBoxOverlap, FastTestMatchesPlainSatOnRandomTriangles) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> coord(-1.0, 5.0);
  std::uniform_int_distribution<int> snap(0, 3);
  size_t overlaps = 0, tested = 0, touching = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    Vec3d v[3];
    for (auto& p : v)
      for (double& x : p) {
        x = coord(rng);
        if (snap(rng) == 0) x = std::round(x);  // many coordinates exactly on voxel planes
      }
    if (trial % 10 == 0) v[2] = v[1];  // some degenerate (segment) triangles
    const TriangleVoxelTest fast(v[0], v[1], v[2]);
    for (int64_t k = fast.firstVoxel(2); k <= fast.lastVoxel(2); ++k)
      for (int64_t j = fast.firstVoxel(1); j <= fast.lastVoxel(1); ++j)
        for (int64_t i = fast.firstVoxel(0); i <= fast.lastVoxel(0); ++i) {
          const bool expected = triangleOverlapsVoxelSat(v[0], v[1], v[2], i, j, k);
          // The two forms round differently; they may differ only where triangle and box
          // merely touch (snapped coordinates make that common here).
          if (fast.overlaps(i, j, k) != expected) {
            ++touching;
            ASSERT_LT(std::abs(separation(v[0], v[1], v[2], i, j, k)), 1e-9)
                << "trial " << trial << " voxel " << i << " " << j << " " << k;
          }
          overlaps += expected;
          ++tested;
        }
    // Outside the bounding box the plain SAT finds nothing either.
    EXPECT_FALSE(triangleOverlapsVoxelSat(v[0], v[1], v[2], fast.lastVoxel(0) + 1,
                                          fast.firstVoxel(1), fast.firstVoxel(2)));
  }
  EXPECT_GT(overlaps, 1000u);
  EXPECT_LT(overlaps, tested);  // the test separates something
  EXPECT_LT(touching * 1000, tested);
}

TEST(TriangleBoxOverlap, TriangleOnAVoxelPlaneBelongsToTheVoxelAbove) {
  // The triangle lies in the plane z = 3, the face between voxels k = 2 and k = 3.
  const Vec3d a{0.2, 0.2, 3.0}, b{0.8, 0.2, 3.0}, c{0.2, 0.8, 3.0};
  EXPECT_TRUE(triangleOverlapsVoxelSat(a, b, c, 0, 0, 3));
  EXPECT_FALSE(triangleOverlapsVoxelSat(a, b, c, 0, 0, 2));
  const TriangleVoxelTest fast(a, b, c);
  EXPECT_EQ(fast.firstVoxel(2), 3);
  EXPECT_EQ(fast.lastVoxel(2), 3);
  EXPECT_TRUE(fast.overlaps(0, 0, 3));
}

TEST(TriangleBoxOverlap, SegmentAndPointAreExact) {
  // A point marks the voxel that contains it; a segment the voxels it passes through.
  const Vec3d p{0.5, 0.5, 0.5};
  EXPECT_TRUE(triangleOverlapsVoxelSat(p, p, p, 0, 0, 0));
  EXPECT_FALSE(triangleOverlapsVoxelSat(p, p, p, 1, 0, 0));
  const Vec3d s0{0.25, 0.5, 0.5}, s1{1.75, 0.5, 0.5};
  EXPECT_TRUE(triangleOverlapsVoxelSat(s0, s1, s1, 1, 0, 0));
  EXPECT_FALSE(triangleOverlapsVoxelSat(s0, s1, s1, 1, 1, 0));
  // A skew segment that passes beside voxel (1,1,0) without touching it (the SAT needs the
  // segment-direction x box-edge axes to see that).
  const Vec3d q0{0.0, 1.9, 0.5}, q1{1.9, 0.0, 0.5};
  EXPECT_TRUE(triangleOverlapsVoxelSat(q0, q1, q1, 0, 0, 0));
  EXPECT_FALSE(triangleOverlapsVoxelSat(q0, q1, q1, 1, 1, 0));
}

}  // namespace
}  // namespace voxlink::geometry
