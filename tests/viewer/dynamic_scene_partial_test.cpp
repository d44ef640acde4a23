// SPDX-License-Identifier: BSD-3-Clause
// Only what moved is re-voxelized (viewer/dynamic_scene.h, docs/dynamic-scenes.md): with two
// moving meshes of which one stops, the stopped one's voxels are kept in the layer and only the
// other is re-voxelized; the layer (every sum, every material) and the frame equal a fresh
// scene's full re-voxelization of the same poses.
#include <gtest/gtest.h>

#include <fstream>

#include "gl_test_context.h"
#include "render/camera.h"
#include "render/gl/render_target.h"
#include "render/image.h"
#include "scene/scene_description.h"
#include "tests/support/test_util.h"
#include "viewer/dynamic_scene.h"

namespace voxlink::viewer {
namespace {

// A static floor, the bunny and a box (objects 1 and 2) that move; the box stands inside the
// bunny's bounds, so some voxels hold both (summed normals, the higher material).
std::string writeScene(const ::voxlink::testing::TempDir& dir) {
  std::ofstream(dir.file("floor.obj")) << "v -0.3 0 -0.3\nv -0.3 0 0.3\nv 0.3 0 0.3\nv 0.3 0 -0.3\n"
                                          "f 1 2 3\nf 1 3 4\n";
  std::ofstream(dir.file("box.obj"))
      << "v -0.02 0.08 -0.02\nv 0.02 0.08 -0.02\nv 0.02 0.12 -0.02\nv -0.02 0.12 -0.02\n"
         "v -0.02 0.08 0.02\nv 0.02 0.08 0.02\nv 0.02 0.12 0.02\nv -0.02 0.12 0.02\n"
         "f 1 3 2\nf 1 4 3\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\n"
         "f 4 7 3\nf 4 8 7\nf 1 5 8\nf 1 8 4\nf 2 3 7\nf 2 7 6\n";
  const std::string path = dir.file("two.scene.json");
  std::ofstream(path) << R"({"grid": {"resolution": 96, "brick": 8},
    "materials": {"jade": {"color": [0.35, 0.65, 0.45]}, "clay": {"color": [0.8, 0.6, 0.5]},
                  "red": {"color": [0.9, 0.1, 0.1]}},
    "objects": [
      {"type": "mesh", "file": "floor.obj", "material": "clay"},
      {"type": "mesh", "file": ")" +
                             ::voxlink::testing::dataPath("mesh/vtk_bunny.ply") +
                             R"(", "material": "jade", "animation": {"keys": [{"time": 0}]}},
      {"type": "mesh", "file": "box.obj", "material": "red", "animation": {"keys": [{"time": 0}]}}]})";
  return path;
}

scene::Pose at(double x, double z, double turn = 0) {
  scene::Pose p;
  p.translate = {x, 0, z};
  p.rotateDegrees = {0, turn, 0};
  return p;
}

render::Image frame(DynamicScene& d) {
  render::CameraSpec spec;
  spec.azimuthDeg = 30;
  spec.elevationDeg = 35;
  spec.up = render::UpAxis::kY;
  const render::Camera camera = render::Camera::framing(d.renderer().geometry().worldBox(), spec);
  render::RenderSettings s;
  s.width = 128;
  s.height = 128;
  render::gl::RenderTarget target;
  const Status st = d.renderer().render(camera, s, target);
  EXPECT_TRUE(st.isOk()) << (st ? "" : st.message());
  return target.read();
}

// The layer and the frame of `d` against a fresh scene's first (full) update of the same poses.
void expectSameAsFresh(DynamicScene& d, const scene::SceneDescription& description,
                       const ::voxlink::testing::TempDir& dir,
                       const std::vector<scene::Pose>& poses) {
  auto fresh = DynamicScene::load(description, dir.file("fresh.vxl"));
  ASSERT_TRUE(fresh) << fresh.message();
  ASSERT_TRUE((*fresh)->setPoses(poses).isOk());
  EXPECT_EQ((*fresh)->stats().keptMeshes, 0u);
  const auto want = (*fresh)->layer().readVoxels();
  ASSERT_GT(want.size(), 1000u);
  EXPECT_TRUE(d.layer().readVoxels() == want);
  EXPECT_EQ(d.layer().lo(), (*fresh)->layer().lo());
  EXPECT_EQ(d.layer().hi(), (*fresh)->layer().hi());
  const render::Image a = frame(d), b = frame(**fresh);
  ASSERT_EQ(a.rgba.size(), b.rgba.size());
  EXPECT_TRUE(a.rgba == b.rgba);  // bit for bit
}

TEST(DynamicScene, OnlyTheMovedMeshIsReVoxelizedAndTheFrameIsTheFullUpdatesFrame) {
  VOXLINK_REQUIRE_GL();
  ::voxlink::testing::TempDir dir;
  auto description = scene::readSceneDescription(writeScene(dir));
  ASSERT_TRUE(description) << description.message();
  auto loaded = DynamicScene::load(*description, dir.file("static.vxl"));
  ASSERT_TRUE(loaded) << loaded.message();
  DynamicScene& d = **loaded;
  ASSERT_EQ(d.movingObjects().size(), 2u);
  const uint64_t all = d.stats().movingTriangles, box = 12, bunny = all - box;

  // The bunny moves every update, the box stands: once still it is re-voxelized with the
  // bunny, twice still it goes into the kept part (re-voxelized once more, alone), from then on
  // only the bunny is.
  const double s = d.grid().spacing;
  const std::vector<uint64_t> reVoxelized = {all, all, all, bunny, bunny};
  const std::vector<uint32_t> kept = {0, 0, 1, 1, 1};
  std::vector<scene::Pose> poses;
  for (size_t u = 0; u < reVoxelized.size(); ++u) {
    poses = {at(-3 * s + double(u) * 1.3 * s, 0, double(u) * 7), at(0, 0)};
    ASSERT_TRUE(d.setPoses(poses).isOk());
    ASSERT_TRUE(d.layer().checkLastUpdate().isOk());
    EXPECT_EQ(d.stats().reVoxelizedTriangles, reVoxelized[u]) << "update " << u;
    EXPECT_EQ(d.stats().keptMeshes, kept[u]) << "update " << u;
  }
  expectSameAsFresh(d, *description, dir, poses);

  // Now the box moves and the bunny stands: the kept part is dropped, then holds the bunny.
  const std::vector<uint64_t> boxMoves = {all, all, box, box};
  const std::vector<uint32_t> keptThen = {0, 1, 1, 1};
  const scene::Pose bunnyStands = poses[0];
  for (size_t u = 0; u < boxMoves.size(); ++u) {
    poses = {bunnyStands, at(2 * s, -double(u) * 0.7 * s)};
    ASSERT_TRUE(d.setPoses(poses).isOk());
    EXPECT_EQ(d.stats().reVoxelizedTriangles, boxMoves[u]) << "update " << u;
    EXPECT_EQ(d.stats().keptMeshes, keptThen[u]) << "update " << u;
  }
  expectSameAsFresh(d, *description, dir, poses);

  // Nothing moves: the box, still once, is re-voxelized on the kept bunny; still twice it joins
  // the kept part (both re-voxelized once more); then nothing is re-voxelized, the same layer.
  const auto before = d.layer().readVoxels();
  const std::vector<uint64_t> stillUpdates = {box, all, 0, 0};
  const std::vector<uint32_t> keptStill = {1, 2, 2, 2};
  for (size_t u = 0; u < stillUpdates.size(); ++u) {
    ASSERT_TRUE(d.setPoses(poses).isOk());
    EXPECT_EQ(d.stats().reVoxelizedTriangles, stillUpdates[u]) << "update " << u;
    EXPECT_EQ(d.stats().keptMeshes, keptStill[u]) << "update " << u;
    EXPECT_TRUE(d.layer().readVoxels() == before) << "update " << u;
  }
}

}  // namespace
}  // namespace voxlink::viewer
