// SPDX-License-Identifier: BSD-3-Clause
// Making a static mesh move in the viewer (viewer/app/detail/mesh_promotion.h, SceneSession::
// promote, DragGesture): what can move and the one-line refusals (no GL), then a static box
// made to move gives the frame of a scene whose box moves from the start, and a Ctrl press on
// the static box followed by a motion drags it (headless EGL, 128x128).
#include "viewer/app/detail/mesh_promotion.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "gl_test_context.h"
#include "render/gl/render_target.h"
#include "render/image.h"
#include "render/render_options.h"
#include "tests/support/test_util.h"
#include "viewer/app/detail/drag_gesture.h"
#include "viewer/app/detail/object_pick.h"
#include "viewer/app/detail/viewer_state.h"
#include "viewer/app/scene_session.h"

namespace voxlink::viewer {
namespace {

// objects: 0 a floor (clay), 1 a box (red), 2 a sphere, 3 a box without a scene material, and
// 4 the bunny, standing (`bunny`: an animation string, or "" for a static bunny).
std::string writeScene(const ::voxlink::testing::TempDir& dir, const std::string& bunny) {
  std::ofstream(dir.file("floor.obj")) << "v -0.3 0 -0.3\nv -0.3 0 0.3\nv 0.3 0 0.3\nv 0.3 0 -0.3\n"
                                          "f 1 2 3\nf 1 3 4\n";
  std::ofstream(dir.file("box.obj"))
      << "v 0.1 0.02 0.1\nv 0.2 0.02 0.1\nv 0.2 0.12 0.1\nv 0.1 0.12 0.1\n"
         "v 0.1 0.02 0.2\nv 0.2 0.02 0.2\nv 0.2 0.12 0.2\nv 0.1 0.12 0.2\n"
         "f 1 3 2\nf 1 4 3\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\n"
         "f 4 7 3\nf 4 8 7\nf 1 5 8\nf 1 8 4\nf 2 3 7\nf 2 7 6\n";
  const std::string path = dir.file("promote.scene.json");
  std::ofstream(path) << R"({"grid": {"resolution": 64, "brick": 8},
    "materials": {"jade": {"color": [0.35, 0.65, 0.45]}, "clay": {"color": [0.8, 0.6, 0.5]},
                  "red": {"color": [0.9, 0.1, 0.1]}},
    "objects": [
      {"type": "mesh", "file": "floor.obj", "material": "clay"},
      {"type": "mesh", "file": "box.obj", "material": "red"},
      {"type": "sphere", "center": [-0.2, 0.05, -0.2], "radius": 0.04, "material": "clay"},
      {"type": "mesh", "file": "box.obj", "transform": {"translate": [-0.3, 0, 0]}},
      {"type": "mesh", "file": ")" +
                             ::voxlink::testing::dataPath("mesh/vtk_bunny.ply") +
                             R"(", "material": "jade")" + bunny + R"(}],
    "camera": {"azimuth": 30, "elevation": 35, "up": "y"}})";
  return path;
}

const char* kStands = R"(, "animation": {"keys": [{"time": 0}]})";

TEST(MeshPromotion, StaticMeshesAndSpheresWithASceneMaterialMoveAndNotTheLastStaticObject) {
  VOXLINK_REQUIRE_DATA("mesh/vtk_bunny.ply");
  ::voxlink::testing::TempDir dir;
  auto scene = scene::readSceneDescription(writeScene(dir, kStands));
  ASSERT_TRUE(scene) << scene.message();
  auto movable = movableStaticObjects(*scene);
  ASSERT_TRUE(movable) << movable.message();
  ASSERT_EQ(movable->size(), 3u);  // the floor, the red box and the sphere
  EXPECT_EQ((*movable)[0].object, 0u);
  EXPECT_EQ((*movable)[1].object, 1u);
  EXPECT_EQ((*movable)[2].object, 2u);
  EXPECT_NEAR((*movable)[1].restBounds.max[0], 0.2, 1e-6);
  EXPECT_NEAR((*movable)[2].restBounds.max[0], -0.16, 1e-6);

  auto moved = withObjectMoving(*scene, 1);
  ASSERT_TRUE(moved) << moved.message();
  ASSERT_TRUE(moved->objects[1].animation.has_value());
  EXPECT_EQ(moved->objects[1].animation->keys.size(), 1u);
  EXPECT_FALSE(moved->objects[1].animation->rotates());

  auto refusal = [&](size_t object) {
    auto r = withObjectMoving(*scene, object);
    EXPECT_FALSE(r);
    return r ? std::string() : r.message();
  };
  auto sphere = withObjectMoving(*scene, 2);
  ASSERT_TRUE(sphere) << sphere.message();
  EXPECT_TRUE(sphere->objects[2].animation.has_value());
  scene::SceneDescription volume = *scene;  // a volume stays static
  volume.objects[2].kind = scene::ObjectKind::kVolume;
  auto refusedVolume = withObjectMoving(volume, 2);
  ASSERT_FALSE(refusedVolume);
  EXPECT_EQ(refusedVolume.message(),
            cat(scene->path,
                ": objects[2]: only meshes, sphere sets and particles move (a volume stays in "
                "the static part)"));
  scene::SceneDescription bare = *scene;  // a sphere without a scene material
  bare.objects[2].material.reset();
  auto refusedBare = withObjectMoving(bare, 2);
  ASSERT_FALSE(refusedBare);
  EXPECT_NE(refusedBare.message().find("objects[2]: moving spheres need a \"material\""),
            std::string::npos);
  EXPECT_NE(refusal(3).find("objects[3]: a moving mesh needs a \"material\""), std::string::npos);
  EXPECT_NE(refusal(4).find("objects[4]: moves already"), std::string::npos);
  EXPECT_NE(refusal(9).find("objects[9] does not exist"), std::string::npos);
  scene::SceneDescription two = *scene;  // the floor and the moving bunny
  two.objects = {scene->objects[0], scene->objects[4]};
  auto last = withObjectMoving(two, 0);
  ASSERT_FALSE(last);
  EXPECT_NE(last.message().find("objects[0]: the last static object cannot move"),
            std::string::npos);
  auto none = movableStaticObjects(two);
  ASSERT_TRUE(none);
  EXPECT_TRUE(none->empty());
}

render::Image frameOf(render::gl::VoxLinkRenderer& renderer, const format::VoxLinkFile& file) {
  const render::RenderOptions options;  // the file's camera and settings, as the viewer's
  auto spec = options.cameraSpec(file);
  auto settings = options.settings(file);
  EXPECT_TRUE(spec && settings);
  settings->width = settings->height = 128;
  render::gl::RenderTarget target;
  const Status st = renderer.render(render::Camera::framing(renderer.geometry().worldBox(), *spec),
                                    *settings, target);
  EXPECT_TRUE(st.isOk()) << (st ? "" : st.message());
  return target.read();
}

TEST(MeshPromotion, AStaticMeshMadeToMoveGivesTheFrameOfTheSceneWhereItMoves) {
  VOXLINK_REQUIRE_GL();
  VOXLINK_REQUIRE_DATA("mesh/vtk_bunny.ply");
  ::voxlink::testing::TempDir dir;
  auto session = SceneSession::prepare(writeScene(dir, kStands), {});
  ASSERT_TRUE(session) << session.message();
  SceneSession& s = **session;
  ASSERT_TRUE(s.attach().isOk());
  ASSERT_TRUE(s.update(0).isOk());
  ASSERT_EQ(s.movingCount(), 1u);
  ASSERT_EQ(s.staticObjects().size(), 3u);  // the floor, the red box and the sphere
  const std::string before = s.volumeFile();

  ASSERT_TRUE(s.promote(1).isOk());
  EXPECT_FALSE(s.promote(0).isOk());  // one at a time
  ASSERT_TRUE(s.promoting().has_value());
  ASSERT_TRUE(s.finishPromotion().isOk());
  EXPECT_FALSE(s.promoting().has_value());
  EXPECT_TRUE(s.takeRebuilt());
  EXPECT_FALSE(s.takeRebuilt());
  EXPECT_FALSE(std::filesystem::exists(before));
  ASSERT_EQ(s.movingCount(), 2u);
  EXPECT_EQ(s.movingIndexOf(1), std::optional<size_t>(0));
  EXPECT_EQ(s.movingIndexOf(4), std::optional<size_t>(1));
  EXPECT_TRUE(s.held(0));
  ASSERT_EQ(s.staticObjects().size(), 2u);  // the floor and the sphere
  auto updated = s.update(0);
  ASSERT_TRUE(updated && *updated);
  ViewerState state;
  ASSERT_TRUE(state.load(s.volumeFile(), false, s.renderer()).isOk());
  const render::Image promoted = frameOf(*state.renderer, *state.file);

  // The scene where the box moves from the start, as `view` would show it.
  ::voxlink::testing::TempDir other;
  std::string text = writeScene(other, kStands);
  auto fresh = scene::readSceneDescription(text);
  ASSERT_TRUE(fresh);
  fresh->objects[1].animation = scene::Animation{{scene::AnimationKey{}}, 0};
  auto dynamic = DynamicScene::load(*fresh, other.file("fresh.vxl"));
  ASSERT_TRUE(dynamic) << dynamic.message();
  ASSERT_TRUE((*dynamic)->setTime(0).isOk());
  ViewerState freshState;
  ASSERT_TRUE(freshState.load(other.file("fresh.vxl"), false, &(*dynamic)->renderer()).isOk());
  EXPECT_EQ(state.file->header().voxelCount, freshState.file->header().voxelCount);
  const render::Image want = frameOf(*freshState.renderer, *freshState.file);
  ASSERT_EQ(promoted.rgba.size(), want.rgba.size());
  EXPECT_TRUE(promoted.rgba == want.rgba);  // bit for bit
  size_t red = 0;                           // the box shows (red where it is lit)
  for (size_t i = 0; i < promoted.rgba.size(); i += 4)
    red += promoted.rgba[i] > 2 * promoted.rgba[i + 1] && promoted.rgba[i + 3] > 0.5f;
  EXPECT_GT(red, 20u);

  // The floor can move too (the box without a material stays static, so the sphere is the last
  // object that can).
  ASSERT_TRUE(s.promote(0).isOk());
  ASSERT_TRUE(s.finishPromotion().isOk());
  EXPECT_EQ(s.movingCount(), 3u);
  ASSERT_EQ(s.staticObjects().size(), 1u);
  EXPECT_EQ(s.staticObjects()[0].object, 2u);
}

TEST(MeshPromotion, ACtrlPressOnAStaticMeshMakesItMoveAndDragsIt) {
  VOXLINK_REQUIRE_GL();
  VOXLINK_REQUIRE_DATA("mesh/vtk_bunny.ply");
  ::voxlink::testing::TempDir dir;
  auto session = SceneSession::prepare(writeScene(dir, ""), {});  // nothing moves
  ASSERT_TRUE(session) << session.message();
  SceneSession& s = **session;
  ASSERT_TRUE(s.attach().isOk());
  EXPECT_FALSE(s.moves());
  ASSERT_EQ(s.staticObjects().size(), 4u);  // floor, red box, sphere, bunny
  render::CameraSpec spec;
  spec.azimuthDeg = 30;
  spec.elevationDeg = 35;
  spec.up = render::UpAxis::kY;
  auto file = format::VoxLinkFile::open(s.volumeFile());
  ASSERT_TRUE(file);
  geometry::VoxelGrid grid;
  for (int a = 0; a < 3; ++a) {
    grid.dims[size_t(a)] = file->header().dims[a];
    grid.origin[size_t(a)] = file->header().origin[a];
  }
  grid.spacing = file->header().spacing[0];
  const geometry::Bounds3 g = scene::gridBox(grid);
  const render::Camera camera = render::Camera::framing(
      {{g.min[0], g.min[1], g.min[2]}, {g.max[0], g.max[1], g.max[2]}}, spec);
  const uint32_t w = 128, h = 128;
  // A pixel whose nearest static box is the red box's (object 1).
  std::optional<std::array<double, 2>> over;
  const auto boxes = s.staticBoxes();
  for (uint32_t y = 0; y < h && !over; y += 2)
    for (uint32_t x = 0; x < w && !over; x += 2) {
      const auto hit = pickBox(camera, x, y, w, h, boxes);
      if (hit && s.staticObjects()[*hit].object == 1) over = {{double(x), double(y)}};
    }
  ASSERT_TRUE(over);

  DragGesture drag;
  auto step = [&](bool left, double dx) {
    auto r =
        drag.update(s, camera, {true, left, (*over)[0] + dx, (*over)[1], {}}, w, h, std::nullopt);
    EXPECT_TRUE(r) << r.message();
    return r && *r;
  };
  EXPECT_TRUE(step(true, 0));  // pressed: the box is being made to move, the camera waits
  EXPECT_TRUE(drag.holding());
  EXPECT_FALSE(drag.active());
  ASSERT_TRUE(s.promoting().has_value());
  EXPECT_EQ(s.promoting()->first, 1u);
  ASSERT_TRUE(s.finishPromotion().isOk());
  EXPECT_TRUE(s.moves());
  EXPECT_TRUE(step(true, 6));  // swapped in: the drag starts from the press
  EXPECT_TRUE(drag.active());
  const auto index = s.movingIndexOf(1);
  ASSERT_TRUE(index.has_value());
  ASSERT_TRUE(s.dragging().has_value());
  EXPECT_EQ(*s.dragging(), *index);
  auto updated = s.update(0);
  ASSERT_TRUE(updated && *updated);
  const scene::Pose& pose = s.dynamic()->pose(*index);
  EXPECT_GT(std::abs(pose.translate[0]) + std::abs(pose.translate[1]) + std::abs(pose.translate[2]),
            1e-3);  // 6 pixels of a 128-pixel view of a 0.6-wide scene: about 0.02
  EXPECT_FALSE(step(false, 6));
  EXPECT_FALSE(drag.holding());
  EXPECT_TRUE(s.held(*index));  // stays where it was dragged

  // With a moving mesh selected, a press over a static mesh (no moving one under it) drags the
  // selected mesh, as before static meshes could move; nothing is promoted.
  std::optional<std::array<double, 2>> overStatic;
  for (uint32_t y = 0; y < h && !overStatic; y += 2)
    for (uint32_t x = 0; x < w && !overStatic; x += 2)
      if (!pickBox(camera, x, y, w, h, s.movingBoxes()) &&
          pickBox(camera, x, y, w, h, s.staticBoxes()))
        overStatic = {{double(x), double(y)}};
  ASSERT_TRUE(overStatic);
  DragGesture second;
  auto r =
      second.update(s, camera, {true, true, (*overStatic)[0], (*overStatic)[1], {}}, w, h, index);
  ASSERT_TRUE(r && *r);
  EXPECT_EQ(s.dragging(), index);
  EXPECT_FALSE(s.promoting().has_value());
  r = second.update(s, camera, {true, false, (*overStatic)[0], (*overStatic)[1], {}}, w, h, index);
  ASSERT_TRUE(r && !*r);
}

}  // namespace
}  // namespace voxlink::viewer
