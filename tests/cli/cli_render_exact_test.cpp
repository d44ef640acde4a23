// SPDX-License-Identifier: BSD-3-Clause
// `voxlink render-exact` as a user runs it: a scene built and compared with its exact image, and
// the inputs it refuses (a volume scene, a .vxl built from another scene, bad effects) with one
// line naming the file and no image left behind.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>

#include "tests/cli/run_command.h"
#include "tests/support/test_util.h"

namespace voxlink::testing {
namespace {

void writeText(const std::string& path, const std::string& text) { std::ofstream(path) << text; }

std::string sphereScene(double radius) {
  return R"({"grid": {"resolution": 48}, "objects": [
      {"type": "sphere", "center": [0, 0, 0], "radius": )" +
         std::to_string(radius) + R"(},
      {"type": "sphere", "center": [1.5, 0, 0], "radius": 0.5}],
      "lights": [{"position": [0, 0, 5]}]})";
}

TEST(CliRenderExact, ComparesTheVoxelSceneWithTheExactOne) {
  TempDir dir;
  const std::string scene = dir.file("spheres.scene.json");
  writeText(scene, sphereScene(1.0));
  auto built = runVoxlink({"scene", "build", scene, "-o", dir.file("spheres.vxl")});
  ASSERT_EQ(built.status, 0) << built.err;
  auto r = runVoxlink({"render-exact", scene, "-o", dir.file("exact.png"), "--size", "32x32",
                       "--effects", "all", "--compare", dir.file("spheres.vxl"), "--voxel-output",
                       dir.file("voxel.exr")});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("exact (Embree 3, 0 triangles, 2 spheres"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("voxel vs exact: PSNR"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("first hit differs"), std::string::npos) << r.out;
  EXPECT_TRUE(std::filesystem::exists(dir.file("exact.png")));
  EXPECT_TRUE(std::filesystem::exists(dir.file("voxel.exr")));
}

TEST(CliRenderExact, RefusesAVolumeScene) {
  TempDir dir;
  const std::string scene = dir.file("foot.scene.json");
  writeText(scene, R"({"objects": [{"type": "volume", "file": "foot.vxl"}]})");
  auto r = runVoxlink({"render-exact", scene, "-o", dir.file("out.png")});
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.err.find("foot.scene.json: objects:"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir.file("out.png")));
}

TEST(CliRenderExact, RefusesAVoxelFileOfAnotherScene) {
  TempDir dir;
  const std::string small = dir.file("small.scene.json"), large = dir.file("large.scene.json");
  writeText(small, sphereScene(1.0));
  writeText(large, sphereScene(3.0));
  ASSERT_EQ(runVoxlink({"scene", "build", large, "-o", dir.file("large.vxl")}).status, 0);
  auto r = runVoxlink(
      {"render-exact", small, "-o", dir.file("out.png"), "--compare", dir.file("large.vxl")});
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.err.find("large.vxl: header: the grid box differs"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir.file("out.png")));
  auto bad = runVoxlink({"render-exact", small, "-o", dir.file("out.png"), "--effects", "mirror"});
  EXPECT_NE(bad.status, 0);
  EXPECT_NE(bad.err.find("mirror"), std::string::npos) << bad.err;
  EXPECT_FALSE(std::filesystem::exists(dir.file("out.png")));
}

}  // namespace
}  // namespace voxlink::testing
