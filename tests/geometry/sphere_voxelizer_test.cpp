// SPDX-License-Identifier: BSD-3-Clause
// voxelizeSpheres against the brute force (every voxel x every sphere).
#include "geometry/sphere_voxelizer.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "tests/geometry/voxel_test_util.h"
#include "tests/support/test_util.h"

namespace voxlink::geometry {
namespace {

void expectMatchesBruteForce(const std::vector<Sphere>& spheres, const VoxelGrid& grid) {
  const auto expected = testing::bruteForceSpheres(spheres, grid);
  auto got = voxelizeSpheres(spheres, grid);
  ASSERT_TRUE(got) << got.message();
  ASSERT_EQ(got->voxels.size(), expected.size());
  ASSERT_EQ(got->offsets.size(), expected.size() + 1);
  size_t n = 0;
  for (const auto& [key, ids] : expected) {
    const auto& v = got->voxels[n];
    ASSERT_EQ(voxelKey(v[0], v[1], v[2]), key);
    const std::vector<uint32_t> gotIds(got->sphereIds.begin() + got->offsets[n],
                                       got->sphereIds.begin() + got->offsets[n + 1]);
    ASSERT_EQ(gotIds, ids);
    ++n;
  }
}

TEST(SphereVoxelizer, RandomSpheresMatchBruteForce) {
  std::mt19937 rng(5);
  VoxelGrid grid;
  grid.origin = {-0.2, 0.3, 0.1};
  grid.spacing = 0.5;
  grid.dims = {14, 12, 10};
  std::uniform_real_distribution<float> x(-2.0f, 8.0f), r(0.05f, 2.5f);
  std::vector<Sphere> spheres;
  for (int s = 0; s < 60; ++s) spheres.push_back({{x(rng), x(rng), x(rng)}, r(rng), 0});
  expectMatchesBruteForce(spheres, grid);
}

// The shell is the solid's voxels that the surface passes through: the farthest corner of the
// voxel's box lies on or outside the sphere. Checked by brute force over every voxel and sphere.
TEST(SphereVoxelizer, ShellKeepsTheVoxelsTheSurfaceCrosses) {
  std::mt19937 rng(11);
  VoxelGrid grid;
  grid.origin = {0.1, -0.3, 0.2};
  grid.spacing = 0.4;
  grid.dims = {20, 18, 16};
  std::uniform_real_distribution<float> x(-1.0f, 7.0f), r(0.1f, 3.0f);
  std::vector<Sphere> spheres;
  for (int s = 0; s < 25; ++s) spheres.push_back({{x(rng), x(rng), x(rng)}, r(rng), 0});
  auto solid = voxelizeSpheres(spheres, grid);
  auto shell = voxelizeSpheres(spheres, grid, kDefaultMaxSphereOverlaps, SphereFill::kShell);
  ASSERT_TRUE(solid && shell);
  std::vector<std::pair<uint64_t, uint32_t>> expected, got;
  for (size_t n = 0; n < solid->voxels.size(); ++n)
    for (uint64_t r0 = solid->offsets[n]; r0 < solid->offsets[n + 1]; ++r0) {
      const Sphere& s = spheres[solid->sphereIds[r0]];
      const auto& v = solid->voxels[n];
      double far2 = 0;
      for (int a = 0; a < 3; ++a) {
        const double lo = grid.origin[a] + (v[a] - 0.5) * grid.spacing, hi = lo + grid.spacing;
        const double d = std::max(std::abs(lo - s.center[a]), std::abs(hi - s.center[a]));
        far2 += d * d;
      }
      if (far2 >= double(s.radius) * s.radius * (1 + 1e-9))
        expected.push_back({voxelKey(v[0], v[1], v[2]), solid->sphereIds[r0]});
    }
  for (size_t n = 0; n < shell->voxels.size(); ++n)
    for (uint64_t r0 = shell->offsets[n]; r0 < shell->offsets[n + 1]; ++r0)
      got.push_back({voxelKey(shell->voxels[n][0], shell->voxels[n][1], shell->voxels[n][2]),
                     shell->sphereIds[r0]});
  EXPECT_LT(got.size(), solid->sphereIds.size());
  // Rounding at the far corner may keep a voxel the world-space check drops (grid vs world units).
  EXPECT_LE(expected.size(), got.size());
  EXPECT_LE(got.size() - expected.size(), got.size() / 1000 + 1);
  for (const auto& e : expected) EXPECT_TRUE(std::binary_search(got.begin(), got.end(), e));
}

TEST(SphereVoxelizer, TouchingExactlyCounts) {
  VoxelGrid grid;  // voxel i covers [i - 0.5, i + 0.5]
  grid.dims = {5, 5, 5};
  // Centre at voxel 2's centre, radius 1.5: reaches exactly the faces of voxels 0 and 4 along
  // the axes (x = 0.5 and 3.5), and the neighbours' far faces.
  const std::vector<Sphere> spheres = {{{2.0f, 2.0f, 2.0f}, 1.5f, 0}};
  auto got = voxelizeSpheres(spheres, grid);
  ASSERT_TRUE(got);
  bool touchesX0 = false;
  for (const auto& v : got->voxels) touchesX0 |= v[0] == 0 && v[1] == 2 && v[2] == 2;
  EXPECT_TRUE(touchesX0);
  expectMatchesBruteForce(spheres, grid);
}

TEST(SphereVoxelizer, BadSpheresAndEmptyInput) {
  VoxelGrid grid;
  grid.dims = {4, 4, 4};
  auto empty = voxelizeSpheres({}, grid);
  ASSERT_TRUE(empty);
  EXPECT_TRUE(empty->voxels.empty());
  EXPECT_EQ(empty->offsets.size(), 1u);
  auto negative = voxelizeSpheres({{{1, 1, 1}, 1, 0}, {{1, 1, 1}, -1, 0}}, grid);
  ASSERT_FALSE(negative);
  EXPECT_NE(negative.message().find("sphere 1"), std::string::npos) << negative.message();
  auto nan = voxelizeSpheres({{{1, std::nanf(""), 1}, 1, 0}}, grid);
  ASSERT_FALSE(nan);
  EXPECT_EQ(nan.code(), ErrorCode::kNonFinite);
  auto limit = voxelizeSpheres({{{2, 2, 2}, 10, 0}}, grid, 10);
  ASSERT_FALSE(limit);
  EXPECT_EQ(limit.code(), ErrorCode::kTooLarge);
}

TEST(SphereVoxelizer, ProteinAtoms) {
  VOXLINK_REQUIRE_DATA("particles/biopython_2XHE.pdb");
  auto set = loadParticles(::voxlink::testing::dataPath("particles/biopython_2XHE.pdb"));
  ASSERT_TRUE(set);
  Bounds3 bounds;
  for (const Sphere& s : set->spheres) {
    bounds.add(s.center[0] - s.radius, s.center[1] - s.radius, s.center[2] - s.radius);
    bounds.add(s.center[0] + s.radius, s.center[1] + s.radius, s.center[2] + s.radius);
  }
  auto grid = fitGrid(bounds, 64);
  ASSERT_TRUE(grid);
  auto got = voxelizeSpheres(set->spheres, *grid);
  ASSERT_TRUE(got) << got.message();
  // Every atom is listed in the voxel holding its centre.
  std::vector<bool> seen(set->spheres.size(), false);
  for (size_t n = 0; n < got->voxels.size(); ++n) {
    for (uint64_t i = got->offsets[n]; i < got->offsets[n + 1]; ++i) {
      const Sphere& s = set->spheres[got->sphereIds[i]];
      const auto c = grid->toGrid(s.center[0], s.center[1], s.center[2]);
      if (uint32_t(c[0]) == got->voxels[n][0] && uint32_t(c[1]) == got->voxels[n][1] &&
          uint32_t(c[2]) == got->voxels[n][2])
        seen[got->sphereIds[i]] = true;
    }
  }
  EXPECT_EQ(std::count(seen.begin(), seen.end(), false), 0);
}

}  // namespace
}  // namespace voxlink::geometry
