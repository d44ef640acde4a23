// SPDX-License-Identifier: BSD-3-Clause
// Keyframed animation in the scene file: parsing, interpolation, loops, and the one-line errors
// (non-finite keys, unsorted times, an object moved outside the grid).
#include "scene/scene_animation.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "scene/scene_description.h"

namespace voxlink::scene {
namespace {

std::string sceneWith(const std::string& animation, const std::string& extra = "") {
  return R"({"materials": {"jade": {"color": [0.3, 0.6, 0.4]}},
             "objects": [{"type": "mesh", "file": "d.ply", "material": "jade")" +
         extra + R"(, "animation": )" + animation + "}]}";
}

std::string problem(const std::string& json) {
  auto r = parseSceneDescription(json, "a.scene.json");
  return r ? "" : r.message();
}

TEST(SceneAnimation, ReadsKeysAndPeriod) {
  auto r = parseSceneDescription(
      sceneWith(R"({"period": 4, "keys": [{"time": 0}, {"time": 1, "translate": [2, 0, 0],
                  "rotate": [0, 0, 90]}]})"),
      "a.scene.json");
  ASSERT_TRUE(r) << r.message();
  ASSERT_TRUE(r->objects[0].animation);
  const Animation& a = *r->objects[0].animation;
  ASSERT_EQ(a.keys.size(), 2u);
  EXPECT_EQ(a.period, 4);
  EXPECT_EQ(a.keys[1].translate[0], 2);
  EXPECT_EQ(a.keys[1].rotateDegrees[2], 90);
  EXPECT_TRUE(a.rotates());
}

TEST(SceneAnimation, InterpolatesLinearlyAndLoops) {
  Animation a;
  a.keys = {{1, {0, 0, 0}, {0, 0, 0}}, {3, {4, -2, 0}, {0, 0, 40}}};
  EXPECT_EQ(samplePose(a, 0).translate[0], 0);  // before the first key: the first key
  EXPECT_DOUBLE_EQ(samplePose(a, 2).translate[0], 2);
  EXPECT_DOUBLE_EQ(samplePose(a, 2).translate[1], -1);
  EXPECT_DOUBLE_EQ(samplePose(a, 2.5).rotateDegrees[2], 30);
  EXPECT_EQ(samplePose(a, 10).translate[0], 4);  // no period: holds the last key
  a.period = 4;  // 3 -> 5 (= 1 + period): back from the last key to the first
  EXPECT_DOUBLE_EQ(samplePose(a, 4).translate[0], 2);
  EXPECT_DOUBLE_EQ(samplePose(a, 0).translate[0], 2);   // 0 is 4 - period
  EXPECT_DOUBLE_EQ(samplePose(a, 6).translate[0], 2);   // 6 mod 4 = 2
  EXPECT_DOUBLE_EQ(samplePose(a, -2).translate[0], 2);  // negative times wrap too
}

TEST(SceneAnimation, ATimeThatIsNotANumberGivesTheFirstKey) {
  // Before: no comparison held for NaN, and the key after it was read past the last one.
  Animation a;
  a.keys = {{1, {7, 0, 0}, {0, 0, 0}}, {3, {4, -2, 0}, {0, 0, 40}}};
  for (double period : {0.0, 4.0}) {
    a.period = period;
    const Pose p = samplePose(a, std::nan(""));
    EXPECT_EQ(p.translate, (std::array<double, 3>{7, 0, 0})) << period;
    EXPECT_EQ(p.rotateDegrees, (std::array<double, 3>{0, 0, 0})) << period;
  }
}

TEST(SceneAnimation, RotatesAboutTheCentreThenTranslates) {
  Pose pose;
  pose.rotateDegrees = {0, 0, 90};
  pose.translate = {10, 0, 0};
  const auto p = applyPose(pose, {1, 1, 1}, {2, 1, 1});  // x offset 1 -> y offset 1
  EXPECT_NEAR(p[0], 11, 1e-12);
  EXPECT_NEAR(p[1], 2, 1e-12);
  EXPECT_NEAR(p[2], 1, 1e-12);
}

TEST(SceneAnimation, BadKeysAreOneLineErrors) {
  // JSON has no NaN or infinity: an overflowing literal fails the parse, a string is no number,
  // and a finite key beyond the range is refused.
  EXPECT_EQ(problem(sceneWith(R"({"keys": [{"time": 0, "translate": [1e999, 0, 0]}]})")),
            "a.scene.json: not valid JSON");
  EXPECT_EQ(problem(sceneWith(R"({"keys": [{"time": 0, "translate": ["NaN", 0, 0]}]})")),
            "a.scene.json: objects[0].animation.keys[0].translate[0]: expected a number");
  EXPECT_EQ(problem(sceneWith(R"({"keys": [{"time": 0, "rotate": [0, 1e300, 0]}]})")),
            "a.scene.json: objects[0].animation.keys[0].rotate[1]: 1e+300 is not in [-3600, "
            "3600]");
  EXPECT_EQ(problem(sceneWith(R"({"keys": [{"time": 2}, {"time": 1}]})")),
            "a.scene.json: objects[0].animation.keys[1].time: 1 is not after keys[0].time (2): "
            "keys must be sorted by time");
  EXPECT_EQ(problem(sceneWith(R"({"keys": [{"time": 0}, {"time": 0}]})")).find("keys[1].time"),
            std::string("a.scene.json: objects[0].animation.").size());
  EXPECT_EQ(problem(sceneWith(R"({"keys": []})")),
            "a.scene.json: objects[0].animation.keys: expected an array of at least one key");
  EXPECT_EQ(problem(sceneWith(R"({"keys": [{"translate": [0, 0, 0]}]})")),
            "a.scene.json: objects[0].animation.keys[0]: needs a \"time\"");
  EXPECT_EQ(problem(sceneWith(R"({"keys": [{"time": 0}, {"time": 3}], "period": 3})")),
            "a.scene.json: objects[0].animation.period: 3 is not after the last key's time (3)");
  EXPECT_EQ(problem(sceneWith(R"({"keys": [{"time": 0, "speed": 1}]})")),
            "a.scene.json: objects[0].animation.keys[0].speed: unknown field");
  EXPECT_EQ(problem(sceneWith(R"({"keys": [{"time": -1}]})")),
            "a.scene.json: objects[0].animation.keys[0].time: -1 is not in [0, 1e+09]");
}

TEST(SceneAnimation, MeshesAndSpheresWithASceneMaterialMoveVolumesDoNot) {
  EXPECT_EQ(problem(R"({"objects": [{"type": "volume", "file": "v.vti",
                         "animation": {"keys": [{"time": 0}]}}]})"),
            "a.scene.json: objects[0].animation: only meshes, sphere sets and particles move (a "
            "volume is not re-voxelized)");
  EXPECT_EQ(problem(R"({"objects": [{"type": "mesh", "file": "d.ply",
                         "animation": {"keys": [{"time": 0}]}}]})"),
            "a.scene.json: objects[0].animation: a moving mesh needs a \"material\" from "
            "\"materials\"");
  EXPECT_EQ(problem(R"({"objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1,
                         "animation": {"keys": [{"time": 0}]}}]})"),
            "a.scene.json: objects[0].animation: moving spheres need a \"material\" from "
            "\"materials\"");
  EXPECT_EQ(problem(R"({"objects": [{"type": "particles", "file": "p.pdb",
                         "animation": {"keys": [{"time": 0}]}}]})"),
            "a.scene.json: objects[0].animation: moving spheres need a \"material\" from "
            "\"materials\"");
  // The same key validation as a mesh's: a key out of range is refused in one line.
  EXPECT_EQ(problem(R"({"materials": {"m": {}}, "objects": [{"type": "sphere", "center": [0, 0, 0],
                         "radius": 1, "material": "m",
                         "animation": {"keys": [{"time": 0, "translate": [0, 1e300, 0]}]}}]})"),
            "a.scene.json: objects[0].animation.keys[0].translate[1]: 1e+300 is not in [-1e+12, "
            "1e+12]");
}

TEST(SceneAnimation, AnObjectMovedOutsideTheGridIsAnError) {
  geometry::VoxelGrid grid;  // covers -0.5 .. 9.5 on every axis
  grid.dims = {10, 10, 10};
  geometry::Bounds3 rest;
  rest.add(1, 1, 1);
  rest.add(3, 3, 3);  // centre 2, half-diagonal sqrt(3)
  Animation a;
  a.keys = {{0, {0, 0, 0}, {0, 0, 0}}, {1, {6, 0, 0}, {0, 0, 0}}};
  EXPECT_TRUE(checkAnimationInGrid(a, rest, grid, "s.json: objects[1]").isOk());
  a.keys.push_back({2, {0, 0, 7}, {0, 0, 0}});
  EXPECT_EQ(checkAnimationInGrid(a, rest, grid, "s.json: objects[1]").message(),
            "s.json: objects[1].animation.keys[2]: moves the object outside the grid (z 8..10 "
            "not in -0.5..9.5)");
  // Rotating 90 degrees about z at x + 5: the keys fit (the box turns into itself), the pose
  // half-way (45 degrees) reaches 2 + 5 + sqrt(2) = 8.41 in x and fits, at x + 6 it does not.
  a.keys = {{0, {0, 0, 0}, {0, 0, 0}}, {1, {5, 0, 0}, {0, 0, 90}}};
  EXPECT_TRUE(checkAnimationInGrid(a, rest, grid, "s.json: objects[1]").isOk());
  a.keys[1].translate[0] = 6.3;  // the key: 7.3 .. 9.3 fits; half-way 3.15 + 3.41 = 6.56 too
  a.keys[1].rotateDegrees[2] = 0;
  EXPECT_TRUE(checkAnimationInGrid(a, rest, grid, "s.json: objects[1]").isOk());
  a.keys[1].rotateDegrees = {0, 0, 45};  // at the key: 2 + 6.3 + sqrt(2) = 9.71 > 9.5
  EXPECT_EQ(
      checkAnimationInGrid(a, rest, grid, "s.json: objects[1]")
          .message()
          .rfind("s.json: objects[1].animation.keys[1]: moves the object outside the grid (x ", 0),
      0u);
  // Only between the keys: 0 -> 90 degrees turns through 45 on the way, at x + 6.5 / 2.
  a.keys = {{0, {6.3, 0, 0}, {0, 0, 0}}, {1, {6.3, 0, 0}, {0, 0, 90}}};
  EXPECT_EQ(
      checkAnimationInGrid(a, rest, grid, "s.json: objects[1]")
          .message()
          .rfind("s.json: objects[1].animation.keys[0]..keys[1]: moves the object outside", 0),
      0u);
  // The loop's way back (last key -> first) is checked too.
  a.keys = {{0, {6.3, 0, 0}, {0, 0, 0}}, {1, {6.3, 0, 0}, {0, 0, 0}}, {2, {6.3, 0, 0}, {0, 0, 90}}};
  EXPECT_NE(
      checkAnimationInGrid(a, rest, grid, "s.json: objects[1]").message().find("keys[1]..keys[2]"),
      std::string::npos);
  a.keys[2].rotateDegrees[2] = 0;
  a.keys[1].rotateDegrees[2] = 360;  // 0 -> 360 -> 0: turns through 45 twice
  EXPECT_NE(
      checkAnimationInGrid(a, rest, grid, "s.json: objects[1]").message().find("keys[0]..keys[1]"),
      std::string::npos);
  // x + 6.3 at 0 degrees, back to x + 0, out to x + 6.3 at 90 degrees: only the loop from
  // keys[2] back to keys[0] turns through 45 degrees near the edge.
  a.keys = {{0, {6.3, 0, 0}, {0, 0, 0}}, {1, {0, 0, 0}, {0, 0, 0}}, {2, {6.3, 0, 0}, {0, 0, 90}}};
  EXPECT_TRUE(checkAnimationInGrid(a, rest, grid, "s.json: objects[1]").isOk());
  a.period = 3;
  EXPECT_NE(
      checkAnimationInGrid(a, rest, grid, "s.json: objects[1]").message().find("keys[2]..keys[0]"),
      std::string::npos);
}

}  // namespace
}  // namespace voxlink::scene
