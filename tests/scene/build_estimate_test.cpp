// SPDX-License-Identifier: BSD-3-Clause
// The scene build's memory estimate against what the voxelizers really store, on the real bunny
// and an implicit sphere, and the one-line refusal when the estimate exceeds the memory.
#include "scene/detail/build_estimate.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "geometry/voxel_grid.h"
#include "scene/scene_assembly.h"
#include "scene/scene_description.h"
#include "tests/support/test_util.h"

namespace voxlink::scene {
namespace {

constexpr const char* kBunny = "mesh/c3dtm_stanford-bunny.obj";

TEST(SceneBuildEstimate, MatchesWhatTheVoxelizersStore) {
  VOXLINK_REQUIRE_DATA(kBunny);
  const auto dir = std::filesystem::temp_directory_path() / "voxlink-build-estimate-test";
  std::filesystem::create_directories(dir);
  const std::string path = (dir / "bunny.scene.json").string();
  std::ofstream(path) << R"({"grid": {"resolution": 384}, "objects": [
      {"type": "mesh", "file": ")"
                      << ::voxlink::testing::dataPath(kBunny) << R"(", "transform": {"scale": 10}},
      {"type": "sphere", "center": [0.9, 0.5, 0.2], "radius": 0.35}]})";
  auto description = readSceneDescription(path);
  ASSERT_TRUE(description) << description.message();
  auto placed = placeSceneGeometry(*description);
  ASSERT_TRUE(placed) << placed.message();
  auto built = buildScene(*description);
  ASSERT_TRUE(built) << built.message();
  const SceneBuildReport& report = built->report;
  ASSERT_GT(report.surfaceVoxels, 100000u);
  ASSERT_GT(report.sphereRefs, 10000u);

  auto grid = geometry::fitGrid(placed->bounds, 384);
  ASSERT_TRUE(grid) << grid.message();
  format::VolumeDescription d;
  for (int a = 0; a < 3; ++a) {
    d.dims[a] = grid->dims[a];
    d.spacing[a] = grid->spacing;
    d.origin[a] = grid->origin[a];
  }
  ASSERT_EQ(d.dims, report.dims);
  const SceneBuildEstimate estimate = estimateSceneBuild(*placed, d, 1234);
  EXPECT_NEAR(estimate.surfaceVoxels / double(report.surfaceVoxels), 1.0, 0.01);
  EXPECT_NEAR(estimate.sphereRefs / double(report.sphereRefs), 1.0, 0.02);
  EXPECT_EQ(estimate.volumeVoxels, 1234.0);
  EXPECT_DOUBLE_EQ(estimate.peakBytes, estimate.surfaceVoxels * kSurfaceVoxelBuildBytes +
                                           estimate.sphereRefs * kSphereRefBuildBytes +
                                           1234.0 * kVolumeVoxelBuildBytes);
  std::filesystem::remove_all(dir);
}

// The voxelizers clip to the grid: on a volume's grid, what lies outside it stores nothing.
TEST(SceneBuildEstimate, LeavesOutWhatLiesOutsideTheGrid) {
  PlacedScene placed;
  placed.mesh.positions = {0, 0, 5,  10, 0, 5,  0, 10, 5,    // inside: 50 voxels of area
                           0, 0, 50, 10, 0, 50, 0, 10, 50};  // beyond z
  placed.mesh.triangles = {0, 1, 2, 3, 4, 5};
  placed.mesh.triangleMaterials = {0, 0};
  placed.spheres.push_back(geometry::Sphere{{5, 5, 5}, 2, 0});
  placed.spheres.push_back(geometry::Sphere{{5, 5, -9}, 2, 0});
  format::VolumeDescription d;
  d.dims = {16, 16, 16};
  d.spacing = {1, 1, 1};
  d.origin = {0, 0, 0};
  const SceneBuildEstimate e = estimateSceneBuild(placed, d, 0);
  EXPECT_DOUBLE_EQ(e.surfaceVoxels, 50.0);
  EXPECT_DOUBLE_EQ(e.sphereRefs, 1.5 * 4.0 * M_PI * 4.0);
}

TEST(SceneBuildEstimate, RefusesWhatExceedsTheMemoryInOneLine) {
  SceneBuildEstimate e;
  e.surfaceVoxels = 20e6;
  e.sphereRefs = 5e6;
  e.peakBytes = 2.6e9;
  EXPECT_TRUE(checkSceneBuildFits(e, uint64_t(3e9), "a.scene.json", 4096, false));
  const Status refused = checkSceneBuildFits(e, uint64_t(2e9), "a.scene.json", 4096, false);
  ASSERT_FALSE(refused);
  EXPECT_EQ(refused.code(), ErrorCode::kTooLarge);
  const std::string m = refused.message();
  EXPECT_EQ(m.rfind("a.scene.json: grid.resolution 4096: ", 0), 0u) << m;
  EXPECT_NE(m.find("25 million voxel entries, 2.6 GB of memory; this process may use 2 GB"),
            std::string::npos)
      << m;
  EXPECT_EQ(m.find('\n'), std::string::npos) << m;
  const Status volume = checkSceneBuildFits(e, uint64_t(1e9), "v.scene.json", 4096, true);
  ASSERT_FALSE(volume);
  EXPECT_EQ(volume.message().rfind("v.scene.json: on the volume's grid: ", 0), 0u)
      << volume.message();
}

TEST(SceneBuildEstimate, MemoryForThisProcessIsPositive) {
  EXPECT_GT(base::memoryForThisProcess(), uint64_t{64} << 20);
}

}  // namespace
}  // namespace voxlink::scene
