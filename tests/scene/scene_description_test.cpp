// SPDX-License-Identifier: BSD-3-Clause
// The scene file: what it accepts, and the one-line errors naming the JSON path of a bad field.
#include "scene/scene_description.h"

#include <gtest/gtest.h>

#include <cmath>

namespace voxlink::scene {
namespace {

std::string problem(const std::string& json) {
  auto r = parseSceneDescription(json, "s.scene.json");
  return r ? "" : r.message();
}

TEST(SceneDescription, ReadsEveryField) {
  auto r = parseSceneDescription(R"({
    "grid": {"resolution": 512, "brick": 16, "axis": "y"},
    "materials": {"glass": {"color": [0.9, 0.9, 1], "transmission": 0.9, "ior": 1.5, "opacity": 0.3},
                  "lamp": {"emission": [4, 4, 3]}},
    "objects": [
      {"type": "mesh", "file": "meshes/bunny.obj", "material": "glass",
       "transform": {"scale": 2, "rotate": [0, 90, 0], "translate": [1, 2, 3]}},
      {"type": "particles", "file": "/abs/mol.pdb", "radius_scale": 0.5},
      {"type": "sphere", "center": [0, 1, 0], "radius": 0.25, "material": "lamp"},
      {"type": "volume", "file": "foot.vxl"}
    ],
    "lights": [{"position": [0, 5, 0], "color": [1, 1, 1], "intensity": 2}],
    "camera": {"azimuth": 10, "elevation": 5, "fov": 40, "up": "y"}
  })",
                                 "dir/s.scene.json");
  ASSERT_TRUE(r) << r.message();
  EXPECT_EQ(r->grid.resolution, 512u);
  EXPECT_EQ(r->grid.brickSize, 16u);
  EXPECT_EQ(r->grid.axis, format::Axis::kY);
  ASSERT_EQ(r->objects.size(), 4u);
  EXPECT_EQ(r->objects[0].path, "dir/meshes/bunny.obj");  // relative to the scene file
  EXPECT_EQ(r->objects[1].path, "/abs/mol.pdb");
  EXPECT_EQ(r->objects[1].radiusScale, 0.5);
  EXPECT_EQ(r->objects[2].radius, 0.25);
  ASSERT_TRUE(r->findMaterial("glass"));
  EXPECT_FLOAT_EQ(r->findMaterial("glass")->material.refractiveIndex, 1.5f);
  EXPECT_FLOAT_EQ(r->findMaterial("lamp")->material.emission[0], 4.0f);
  // scale 2, then 90 degrees about y (x -> -z), then the translation.
  const auto p = r->objects[0].transform.apply({1, 0, 0});
  EXPECT_NEAR(p[0], 1, 1e-12);
  EXPECT_NEAR(p[1], 2, 1e-12);
  EXPECT_NEAR(p[2], 3 - 2, 1e-12);
  EXPECT_NEAR(r->objects[0].transform.uniformScale(), 2.0, 1e-12);
  EXPECT_EQ(r->lights.size(), 1u);
  EXPECT_NE(r->cameraJson.find("azimuth"), std::string::npos);
}

TEST(SceneDescription, DefaultsWhenSilent) {
  auto r = parseSceneDescription(
      R"({"objects": [{"type": "sphere", "center": [0,0,0], "radius": 1}]})", "s.json");
  ASSERT_TRUE(r) << r.message();
  EXPECT_EQ(r->grid.resolution, 256u);
  EXPECT_EQ(r->grid.brickSize, 8u);
  EXPECT_EQ(r->grid.axis, format::Axis::kZ);
}

TEST(SceneDescription, ErrorsNameTheField) {
  EXPECT_EQ(problem("{"), "s.scene.json: not valid JSON");
  EXPECT_NE(problem(R"({"objects": 3})").find("objects: expected an array"), std::string::npos);
  EXPECT_NE(problem(R"({"objects": [{"type": "sphere", "center": [0,0,0], "radius": -1}]})")
                .find("objects[0].radius: -1 is not in"),
            std::string::npos)
      << problem(R"({"objects": [{"type": "sphere", "center": [0,0,0], "radius": -1}]})");
  EXPECT_NE(problem(R"({"objects": [{"type": "cube"}]})").find("objects[0].type: \"cube\""),
            std::string::npos);
  EXPECT_NE(problem(R"({"objects": [{"type": "mesh"}]})").find("objects[0]: needs a \"file\""),
            std::string::npos);
  EXPECT_NE(problem(R"({"objects": [{"type": "mesh", "file": "a.obj", "material": "nope"}]})")
                .find("objects[0].material: \"nope\" is not in \"materials\""),
            std::string::npos);
  EXPECT_NE(problem(R"({"grid": {"brick": 12}, "objects": []})").find("grid.brick"),
            std::string::npos);
  EXPECT_NE(problem(R"({"grid": {"resolution": 1}, "objects": []})").find("grid.resolution"),
            std::string::npos);
  EXPECT_NE(problem(R"({"grid": {"resoluton": 64}, "objects": []})")
                .find("grid.resoluton: unknown field"),
            std::string::npos);
  EXPECT_NE(
      problem(R"({"materials": {"m": {"reflectivity": 0.7, "transmission": 0.5}}, "objects": []})")
          .find("materials.m: reflectivity + transmission exceed 1"),
      std::string::npos);
  EXPECT_NE(problem(R"({"materials": {"m": {"color": [1, 0, "x"]}}, "objects": []})")
                .find("materials.m.color[2]"),
            std::string::npos);
  EXPECT_NE(
      problem(
          R"({"objects": [{"type": "volume", "file": "a.vxl"}, {"type": "volume", "file": "b.vxl"}]})")
          .find("at most one volume"),
      std::string::npos);
  EXPECT_NE(
      problem(
          R"({"objects": [{"type": "particles", "file": "a.pdb", "transform": {"scale": [1, 2, 1]}}]})")
          .find("uniform scale"),
      std::string::npos);
  EXPECT_NE(
      problem(
          R"({"objects": [{"type": "mesh", "file": "a.obj", "transform": {"matrix": [1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,1,1]}}]})")
          .find("last row must be 0 0 0 1"),
      std::string::npos);
  EXPECT_NE(problem(R"({"objects": [], "camera": {"up": "x"}})").find("camera.up"),
            std::string::npos);
  EXPECT_NE(problem(R"({"objects": [], "lights": [{"color": [1,1,1]}]})")
                .find("lights[0]: needs a \"position\""),
            std::string::npos);
}

TEST(SceneDescription, MissingFileIsOneLine) {
  auto r = readSceneDescription("/nonexistent/x.scene.json");
  ASSERT_FALSE(r);
  EXPECT_EQ(r.message().find('\n'), std::string::npos);
  EXPECT_NE(r.message().find("/nonexistent/x.scene.json"), std::string::npos);
}

}  // namespace
}  // namespace voxlink::scene
