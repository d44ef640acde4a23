// SPDX-License-Identifier: BSD-3-Clause
// Slabs of z slices (what one MPI rank voxelizes, scene/detail/scene_ranks.h): the surface and
// sphere voxelizers' results over slabs that tile the grid concatenate to the whole grid's result,
// fragment for fragment, and the normal-error tallies merge to the same statistics.
#include <gtest/gtest.h>

#include <cstring>

#include "geometry/mesh_loader.h"
#include "geometry/normal_error.h"
#include "geometry/particle_loader.h"
#include "geometry/sphere_voxelizer.h"
#include "geometry/surface_voxelizer.h"
#include "tests/support/test_util.h"

namespace voxlink::geometry {
namespace {

bool sameVoxel(const SurfaceVoxel& a, const SurfaceVoxel& b) {
  return a.x == b.x && a.y == b.y && a.z == b.z && a.material == b.material &&
         std::memcmp(a.normal.data(), b.normal.data(), sizeof a.normal) == 0;
}

bool sameStats(const NormalErrorStats& a, const NormalErrorStats& b) {
  return a.pairs == b.pairs && a.multiTriangleVoxels == b.multiTriangleVoxels &&
         a.meanDegrees == b.meanDegrees && a.p95Degrees == b.p95Degrees &&
         a.maxDegrees == b.maxDegrees;
}

TEST(VoxelizerSlabs, SurfaceSlabsConcatenateToTheWholeGrid) {
  VOXLINK_REQUIRE_DATA("mesh/c3dtm_stanford-bunny.obj");
  auto mesh = loadMesh(testing::dataPath("mesh/c3dtm_stanford-bunny.obj"));
  ASSERT_TRUE(mesh) << mesh.message();
  auto grid = fitGrid(meshBounds(*mesh), 150);
  ASSERT_TRUE(grid) << grid.message();
  auto whole = voxelizeSurface(*mesh, *grid);
  ASSERT_TRUE(whole) << whole.message();
  // Uneven slabs, one empty, the last one past the grid's end.
  const uint32_t cuts[] = {0, 13, 13, 64, 101, 400};
  std::vector<SurfaceVoxel> joined;
  NormalErrorTally tally;
  for (size_t s = 0; s + 1 < std::size(cuts); ++s) {
    SurfaceVoxelizeOptions options;
    options.slab = {cuts[s], cuts[s + 1]};
    auto part = voxelizeSurface(*mesh, *grid, options);
    ASSERT_TRUE(part) << part.message();
    for (const SurfaceVoxel& v : part->voxels) {
      EXPECT_GE(v.z, cuts[s]);
      EXPECT_LT(v.z, cuts[s + 1]);
    }
    joined.insert(joined.end(), part->voxels.begin(), part->voxels.end());
    ASSERT_TRUE(part->normalTally);
    tally.merge(*part->normalTally);
  }
  ASSERT_EQ(joined.size(), whole->voxels.size());
  ASSERT_GT(joined.size(), 10000u);
  for (size_t i = 0; i < joined.size(); ++i)
    ASSERT_TRUE(sameVoxel(joined[i], whole->voxels[i])) << "voxel " << i;
  EXPECT_TRUE(sameStats(tally.stats(), whole->normalError));
  EXPECT_GT(whole->normalError.meanDegrees, 0.0);
}

TEST(VoxelizerSlabs, SphereSlabsConcatenateToTheWholeGrid) {
  VOXLINK_REQUIRE_DATA("particles/biopython_2XHE.pdb");
  auto set = loadParticles(testing::dataPath("particles/biopython_2XHE.pdb"));
  ASSERT_TRUE(set) << set.message();
  Bounds3 bounds;
  for (const Sphere& s : set->spheres)
    for (int a = 0; a < 3; ++a) {
      bounds.min[a] = std::min(bounds.min[a], s.center[a] - s.radius);
      bounds.max[a] = std::max(bounds.max[a], s.center[a] + s.radius);
    }
  auto grid = fitGrid(bounds, 90);
  ASSERT_TRUE(grid) << grid.message();
  auto whole = voxelizeSpheres(set->spheres, *grid, kDefaultMaxSphereOverlaps, SphereFill::kShell);
  ASSERT_TRUE(whole) << whole.message();
  std::vector<std::array<uint32_t, 3>> voxels;
  std::vector<uint32_t> ids;
  std::vector<uint64_t> counts;
  for (auto [from, to] : {std::pair{0u, 30u}, {30u, 31u}, {31u, 88u}, {88u, 1000u}}) {
    auto part = voxelizeSpheres(set->spheres, *grid, kDefaultMaxSphereOverlaps, SphereFill::kShell,
                                ZSlab{from, to});
    ASSERT_TRUE(part) << part.message();
    voxels.insert(voxels.end(), part->voxels.begin(), part->voxels.end());
    ids.insert(ids.end(), part->sphereIds.begin(), part->sphereIds.end());
    for (size_t n = 0; n + 1 < part->offsets.size(); ++n)
      counts.push_back(part->offsets[n + 1] - part->offsets[n]);
  }
  EXPECT_EQ(voxels, whole->voxels);
  EXPECT_EQ(ids, whole->sphereIds);
  ASSERT_EQ(counts.size() + 1, whole->offsets.size());
  for (size_t n = 0; n < counts.size(); ++n)
    EXPECT_EQ(counts[n], whole->offsets[n + 1] - whole->offsets[n]);
}

// The tally's sum is fixed point: merging in any order, or sending it as words, changes nothing.
TEST(NormalErrorTally, MergeOrderAndWordsDoNotChangeTheStatistics) {
  NormalErrorTally a, b, all;
  for (int i = 0; i < 1000; ++i) {
    const double degrees = 0.001 * i * i / 7.0 + 1e-7 * i;
    (i % 3 ? a : b).add(degrees);
    all.add(degrees);
  }
  a.countMultiTriangleVoxel();
  all.countMultiTriangleVoxel();
  NormalErrorTally ab = a, ba = b;
  ab.merge(b);
  ba.merge(a);
  EXPECT_TRUE(sameStats(ab.stats(), all.stats()));
  EXPECT_TRUE(sameStats(ba.stats(), all.stats()));
  const std::vector<uint64_t> words = ab.words();
  ASSERT_EQ(words.size(), NormalErrorTally::kWords);
  EXPECT_TRUE(sameStats(NormalErrorTally::fromWords(words.data()).stats(), all.stats()));
  EXPECT_NEAR(all.stats().meanDegrees, 0.001 / 7.0 * 332833500.0 / 1000.0 + 1e-7 * 499.5, 1e-5);
}

}  // namespace
}  // namespace voxlink::geometry
