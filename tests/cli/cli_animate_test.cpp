// SPDX-License-Identifier: BSD-3-Clause
// `voxlink bench-render --animate SCENE.json` as a user runs it: one row per resolution, brick
// size and image size with finite times, and one-line errors for a scene that does not move, an
// animation that leaves the grid, and --resolutions without --animate.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "tests/cli/run_command.h"
#include "tests/support/test_util.h"

namespace voxlink::testing {
namespace {

std::string sceneFile(const TempDir& dir, const std::string& animation) {
  std::ofstream(dir.file("floor.obj")) << "v -8 0 -8\nv -8 0 8\nv 8 0 8\nv 8 0 -8\n"
                                          "f 1 2 3\nf 1 3 4\n";
  const std::string path = dir.file("a.scene.json");
  std::ofstream(path) << R"({"grid": {"resolution": 48},
    "materials": {"jade": {"color": [0.3, 0.6, 0.4]}},
    "objects": [{"type": "mesh", "file": "floor.obj"},
                {"type": "mesh", "file": ")" +
                             dataPath("mesh/bunny_npm.obj") + R"(", "material": "jade")" +
                             animation + "}], \"camera\": {\"up\": \"y\"}}";
  return path;
}

int lineCount(const std::string& text) {
  std::istringstream in(text);
  std::string line;
  int n = 0;
  while (std::getline(in, line)) ++n;
  return n;
}

TEST(CliAnimate, PrintsOneRowPerResolutionBrickAndSize) {
  VOXLINK_REQUIRE_DATA("mesh/bunny_npm.obj");
  TempDir dir;
  const std::string scene = sceneFile(
      dir, R"(, "animation": {"period": 1, "keys": [{"time": 0}, {"time": 0.5, "translate":
               [1.5, 0, 0], "rotate": [0, 30, 0]}]})");
  auto r = runVoxlink({"bench-render", "--animate", scene, "--resolutions", "32", "48", "--bricks",
                       "4", "8", "--sizes", "32x32", "--frames", "3"});
  ASSERT_EQ(r.status, 0) << r.err;
  for (const char* row :
       {"| 32 | 4 | 32x32 |", "| 32 | 8 | 32x32 |", "| 48 | 4 | 32x32 |", "| 48 | 8 | 32x32 |"})
    EXPECT_NE(r.out.find(row), std::string::npos) << row << "\n" << r.out;
  EXPECT_EQ(r.out.find("nan"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("inf"), std::string::npos) << r.out;
}

TEST(CliAnimate, AMovingSphereIsCountedAndTheStaticFrameIsTimed) {
  TempDir dir;
  std::ofstream(dir.file("floor.obj"))
      << "v -8 0 -8\nv -8 0 8\nv 8 0 8\nv 8 0 -8\nf 1 2 3\nf 1 3 4\n";
  const std::string scene = dir.file("s.scene.json");
  std::ofstream(scene) << R"({"grid": {"resolution": 32},
    "materials": {"jade": {"color": [0.3, 0.6, 0.4]}},
    "objects": [{"type": "mesh", "file": "floor.obj", "material": "jade"},
                {"type": "sphere", "center": [0, 2, 0], "radius": 1.5, "material": "jade",
                 "animation": {"keys": [{"time": 0}, {"time": 1, "translate": [3, 0, 0]}]}}],
    "camera": {"up": "y"}})";
  auto r = runVoxlink({"bench-render", "--animate", scene, "--sizes", "32x32", "--frames", "3"});
  ASSERT_EQ(r.status, 0) << r.err;
  // | 32 | brick | 32x32 | 0 triangles | MB | s | vox | render | median | p95 | FPS | 1 | static |
  const size_t row = r.out.find("| 32 | 8 | 32x32 | 0 |");
  ASSERT_NE(row, std::string::npos) << r.out;
  const std::string line = r.out.substr(row, r.out.find('\n', row) - row);
  int bars = 0;
  for (char c : line) bars += c == '|' ? 1 : 0;
  EXPECT_EQ(bars, 14) << line;
  EXPECT_NE(line.find(" | 1 | "), std::string::npos) << line;
  EXPECT_EQ(line.find("nan"), std::string::npos) << line;
}

TEST(CliAnimate, BadScenesAreOneLineErrors) {
  VOXLINK_REQUIRE_DATA("mesh/bunny_npm.obj");
  TempDir dir;
  auto still = runVoxlink({"bench-render", "--animate", sceneFile(dir, ""), "--sizes", "16x16"});
  EXPECT_NE(still.status, 0);
  EXPECT_EQ(lineCount(still.err), 1) << still.err;
  EXPECT_NE(still.err.find("a.scene.json: objects: no object has an \"animation\""),
            std::string::npos)
      << still.err;
  auto away = runVoxlink(
      {"bench-render", "--animate",
       sceneFile(dir,
                 R"(, "animation": {"keys": [{"time": 0}, {"time": 1, "translate": [0, 9, 0]}]})"),
       "--sizes", "16x16"});
  EXPECT_NE(away.status, 0);
  EXPECT_EQ(lineCount(away.err), 1) << away.err;
  EXPECT_NE(away.err.find("objects[1].animation.keys[1]: moves the object outside the grid (y "),
            std::string::npos)
      << away.err;
  auto flags = runVoxlink({"bench-render", sceneFile(dir, ""), "--resolutions", "32"});
  EXPECT_NE(flags.status, 0);
  EXPECT_NE(flags.err.find("--resolutions and --bricks need --animate"), std::string::npos)
      << flags.err;
}

}  // namespace
}  // namespace voxlink::testing
