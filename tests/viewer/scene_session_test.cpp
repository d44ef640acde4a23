// SPDX-License-Identifier: BSD-3-Clause
// A scene file in the viewer (viewer/app/scene_session.h, drag_gesture.h) without a window:
// bad scenes fail before any GL, a static scene is built as `scene build` builds it, the first
// frame of a moving scene is the frame `bench-render --animate` draws for the same time (the
// same steps: DynamicScene, the file's default TF and camera), and a modifier + left drag over
// the moving mesh moves it in the view plane, clamped into the grid.
#include "viewer/app/scene_session.h"

#include <epoxy/gl.h>
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

namespace voxlink::viewer {
namespace {

using render::Camera;
using render::Image;

// A static floor and the bunny moving along x (turning on the way back), or standing still.
std::string writeScene(const ::voxlink::testing::TempDir& dir, const std::string& animation) {
  std::ofstream(dir.file("floor.obj")) << "v -0.3 0 -0.3\nv -0.3 0 0.3\nv 0.3 0 0.3\nv 0.3 0 -0.3\n"
                                          "f 1 2 3\nf 1 3 4\n";
  const std::string path = dir.file("moving.scene.json");
  std::ofstream(path) << R"({"grid": {"resolution": 96, "brick": 8},
    "materials": {"jade": {"color": [0.35, 0.65, 0.45]}, "clay": {"color": [0.8, 0.6, 0.5]}},
    "objects": [
      {"type": "mesh", "file": "floor.obj", "material": "clay"},
      {"type": "mesh", "file": ")" +
                             ::voxlink::testing::dataPath("mesh/vtk_bunny.ply") +
                             R"(", "material": "jade")" + animation + R"(}],
    "camera": {"azimuth": 30, "elevation": 35, "up": "y"}})";
  return path;
}

const char* kMoves = R"(, "animation": {"period": 2, "keys": [
    {"time": 0, "translate": [-0.1, 0, 0]},
    {"time": 1, "translate": [0.1, 0, 0.05], "rotate": [0, 60, 0]}]})";

Image render128(render::gl::VoxLinkRenderer& renderer, const Camera& camera,
                render::RenderSettings settings) {
  settings.width = settings.height = 128;
  render::gl::RenderTarget target;
  const Status st = renderer.render(camera, settings, target);
  EXPECT_TRUE(st.isOk()) << (st ? "" : st.message());
  return target.read();
}

double coverage(const Image& image) {
  size_t covered = 0;
  for (size_t i = 3; i < image.rgba.size(); i += 4) covered += image.rgba[i] > 0.5f;
  return double(covered) / double(image.width * image.height);
}

TEST(ViewerSceneSession, BadScenesFailBeforeAnyGl) {
  ::voxlink::testing::TempDir dir;
  // Not JSON: the reader's one line, as `scene build` prints it.
  std::ofstream(dir.file("bad.scene.json")) << "{\"objects\": [";
  auto bad = SceneSession::prepare(dir.file("bad.scene.json"), {});
  ASSERT_FALSE(bad);
  auto read = scene::readSceneDescription(dir.file("bad.scene.json"));
  ASSERT_FALSE(read);
  EXPECT_EQ(bad.message(), read.message());
  // A key that leaves the grid: found while preparing (no GL), one line naming the field.
  VOXLINK_REQUIRE_DATA("mesh/vtk_bunny.ply");
  auto far = SceneSession::prepare(
      writeScene(dir,
                 R"(, "animation": {"keys": [{"time": 0}, {"time": 1, "translate": [9, 0, 0]}]})"),
      {32, 8});
  ASSERT_FALSE(far);
  EXPECT_NE(far.message().find("moving.scene.json: objects[1].animation.keys[1]: moves the "
                               "object outside the grid"),
            std::string::npos)
      << far.message();
  EXPECT_EQ(far.message().find('\n'), std::string::npos);
}

TEST(ViewerSceneSession, AStaticSceneIsBuiltAsSceneBuildBuildsIt) {
  VOXLINK_REQUIRE_DATA("mesh/vtk_bunny.ply");
  ::voxlink::testing::TempDir dir;
  const std::string path = writeScene(dir, "");
  std::string scratch;
  {
    auto session = SceneSession::prepare(path, {40, 4});
    ASSERT_TRUE(session) << session.message();
    EXPECT_FALSE((*session)->moves());
    ASSERT_TRUE((*session)->attach().isOk());
    EXPECT_EQ((*session)->renderer(), nullptr);  // the viewer draws the file itself
    scratch = (*session)->volumeFile();
    auto file = format::VoxLinkFile::open(scratch);
    ASSERT_TRUE(file) << file.message();
    auto description = scene::readSceneDescription(path);
    ASSERT_TRUE(description);
    description->grid.resolution = 40;  // what --resolution 40 --brick 4 give scene build
    description->grid.brickSize = 4;
    auto built = scene::buildScene(*description);
    ASSERT_TRUE(built) << built.message();
    EXPECT_EQ(file->header().voxelCount, built->volume.voxelCount());
    EXPECT_EQ(file->header().brickSize, 4u);
    EXPECT_EQ(std::max({file->header().dims[0], file->header().dims[1], file->header().dims[2]}),
              40u);
  }
  EXPECT_FALSE(std::filesystem::exists(scratch));  // the session removes its scratch file
}

TEST(ViewerSceneSession, FirstFrameIsTheAnimateBenchmarksFrame) {
  VOXLINK_REQUIRE_GL();
  VOXLINK_REQUIRE_DATA("mesh/vtk_bunny.ply");
  ::voxlink::testing::TempDir dir;
  const std::string path = writeScene(dir, kMoves);
  const render::RenderOptions options;  // no flags: the file's TF, camera and settings
  // The viewer's steps: prepare, attach in the window's context, load the file with the
  // session's renderer, start at a time (`view --time 0.5`).
  auto session = SceneSession::prepare(path, {64, 8});
  ASSERT_TRUE(session) << session.message();
  SceneSession& s = **session;
  ASSERT_TRUE(s.moves());
  ASSERT_TRUE(s.attach().isOk());
  ViewerState state;
  ASSERT_TRUE(state.load(s.volumeFile(), false, s.renderer()).isOk());
  auto spec = options.cameraSpec(*state.file);
  auto settings = options.settings(*state.file);
  ASSERT_TRUE(spec && settings);
  const Camera camera = Camera::framing(state.renderer->geometry().worldBox(), *spec);
  s.setTime(0.5);
  auto updated = s.update(0);
  ASSERT_TRUE(updated && *updated);
  const Image viewer = render128(*state.renderer, camera, *settings);

  // bench-render --animate's steps (cli/bench_animate.cpp) for the same time.
  auto description = scene::readSceneDescription(path);
  ASSERT_TRUE(description);
  description->grid.resolution = 64;
  auto dynamic = DynamicScene::load(*description, dir.file("bench-static.vxl"));
  ASSERT_TRUE(dynamic) << dynamic.message();
  auto file = format::VoxLinkFile::open(dir.file("bench-static.vxl"));
  ASSERT_TRUE(file);
  auto tf = options.transferFunction(*file);
  ASSERT_TRUE(tf);
  (*dynamic)->renderer().setTransferFunction(*tf);
  ASSERT_TRUE((*dynamic)->setTime(0.5).isOk());
  glFinish();  // as bench-render --animate does between the update and the frame
  const Image bench = render128(
      (*dynamic)->renderer(),
      Camera::framing((*dynamic)->renderer().geometry().worldBox(), *options.cameraSpec(*file)),
      *settings);

  EXPECT_GT(coverage(viewer), 0.05);  // not an empty frame
  auto error = render::compareImages(viewer, bench);
  ASSERT_TRUE(error);
  // The same frame, pixel for pixel (docs/dynamic-scenes.md: it was not while the layer's walk
  // could read past a brick's face).
  EXPECT_EQ(error->pixelsOver, 0u) << "PSNR " << error->psnr << ", max " << error->maxError;
  // The moving mesh is in it: another time gives another frame.
  s.setTime(1.0);
  ASSERT_TRUE(s.update(0).isOk());
  auto moved = render::compareImages(render128(*state.renderer, camera, *settings), viewer);
  ASSERT_TRUE(moved);
  EXPECT_GT(moved->pixelsOver, 20u);
}

TEST(ViewerSceneSession, ModifierDragMovesTheObjectUnderTheCursorWithinTheGrid) {
  VOXLINK_REQUIRE_GL();
  VOXLINK_REQUIRE_DATA("mesh/vtk_bunny.ply");
  ::voxlink::testing::TempDir dir;
  auto session = SceneSession::prepare(writeScene(dir, kMoves), {48, 8});
  ASSERT_TRUE(session) << session.message();
  SceneSession& s = **session;
  ASSERT_TRUE(s.attach().isOk());
  s.clock().setPlaying(false);
  ASSERT_TRUE(s.update(0).isOk());
  ASSERT_EQ(s.movingCount(), 1u);
  EXPECT_NE(s.movingName(0).find("objects[1] vtk_bunny.ply"), std::string::npos);
  render::CameraSpec spec;  // the scene file's camera: the floor below, the bunny on it
  spec.azimuthDeg = 30;
  spec.elevationDeg = 35;
  spec.up = render::UpAxis::kY;
  const Camera camera = Camera::framing(s.gridBox(), spec);
  const uint32_t w = 128, h = 128;
  // A pixel over the bunny's box, and one over nothing.
  std::optional<std::array<double, 2>> over, empty;
  for (uint32_t y = 0; y < h; y += 4)
    for (uint32_t x = 0; x < w; x += 4) {
      const bool hit = pickBox(camera, x, y, w, h, s.movingBoxes()).has_value();
      if (hit && !over) over = {{double(x), double(y)}};
      if (!hit && !empty) empty = {{double(x), double(y)}};
    }
  ASSERT_TRUE(over && empty);
  const scene::Pose before = s.dynamic()->pose(0);

  DragGesture drag;
  auto step = [&](bool modifier, bool left, double x, double y) {
    auto r = drag.update(s, camera, {modifier, left, x, y, {}}, w, h, std::nullopt);
    EXPECT_TRUE(r) << r.message();
    return r && *r;
  };
  // Without the modifier, or over nothing with no object selected: the camera's drag.
  EXPECT_FALSE(step(false, true, (*over)[0], (*over)[1]));
  EXPECT_FALSE(step(false, false, (*over)[0], (*over)[1]));
  EXPECT_FALSE(step(true, true, (*empty)[0], (*empty)[1]));
  EXPECT_FALSE(step(true, false, (*empty)[0], (*empty)[1]));
  EXPECT_FALSE(s.held(0));
  // Ctrl + press over the bunny, then 6 pixels right: moved by viewPlaneTranslation.
  EXPECT_TRUE(step(true, true, (*over)[0], (*over)[1]));
  EXPECT_TRUE(step(true, true, (*over)[0] + 6, (*over)[1]));
  EXPECT_TRUE(s.held(0));
  auto updated = s.update(0);
  ASSERT_TRUE(updated) << updated.message();
  EXPECT_TRUE(*updated);
  const render::Box box = s.dynamic()->posedBox(0, before);
  auto expected = viewPlaneTranslation(camera, box.center(), 6, 0, h);
  ASSERT_TRUE(expected);
  for (int a = 0; a < 3; ++a)
    EXPECT_NEAR(s.dynamic()->pose(0).translate[size_t(a)],
                before.translate[size_t(a)] + (*expected)[a], 1e-12);
  EXPECT_EQ(s.lastClamp(), (std::array<bool, 3>{false, false, false}));
  // Far to the right (the modifier counts at the press only): clamped to the grid, the pose
  // accepted by DynamicScene, the clamp reported.
  EXPECT_TRUE(step(false, true, (*over)[0] + 1e4, (*over)[1]));
  ASSERT_TRUE(s.update(0).isOk());
  const auto& clamp = s.lastClamp();
  EXPECT_TRUE(clamp[0] || clamp[1] || clamp[2]);
  const render::Box moved = s.dynamic()->posedBox(0, s.dynamic()->pose(0));
  const render::Box grid = s.gridBox();
  for (int a = 0; a < 3; ++a) {
    EXPECT_GE(moved.lo[a], grid.lo[a] - 1e-9);
    EXPECT_LE(moved.hi[a], grid.hi[a] + 1e-9);
  }
  ASSERT_TRUE(s.dynamic()->layer().checkLastUpdate().isOk());
  // Released, the cursor back at the press: the drag ends there (the release position
  // counts), the object stays where it was dragged until sent back.
  EXPECT_FALSE(step(false, false, (*over)[0], (*over)[1]));
  EXPECT_TRUE(s.held(0));
  ASSERT_TRUE(s.update(0).isOk());
  EXPECT_EQ(s.dynamic()->pose(0).translate, before.translate);
  s.clock().setPlaying(true);
  EXPECT_FALSE(*s.update(0.25));  // only the held object moves: nothing to re-voxelize
  s.release(0);
  EXPECT_TRUE(*s.update(0));
  EXPECT_EQ(s.dynamic()->pose(0).translate,
            scene::samplePose(*s.dynamic()->description().objects[1].animation, s.clock().time())
                .translate);
  // A selected object is dragged from anywhere with the modifier.
  EXPECT_TRUE(
      drag.update(s, camera, {true, true, (*empty)[0], (*empty)[1], {}}, w, h, size_t(0)).value());
  EXPECT_FALSE(step(false, false, (*empty)[0], (*empty)[1]));
  // A press seen a frame late, the cursor 6 pixels on: the drag starts where it went down.
  s.release(0);
  s.clock().setPlaying(false);
  s.setTime(0);  // where `over` was found over the bunny
  ASSERT_TRUE(s.update(0).isOk());
  const scene::Pose start = s.dynamic()->pose(0);
  PointerState late{true, true, (*over)[0] + 6, (*over)[1], std::array{(*over)[0], (*over)[1]}};
  DragGesture fresh;
  EXPECT_TRUE(fresh.update(s, camera, late, w, h, std::nullopt).value());
  ASSERT_TRUE(s.update(0).isOk());
  auto six = viewPlaneTranslation(camera, s.dynamic()->posedBox(0, start).center(), 6, 0, h);
  ASSERT_TRUE(six);
  for (int a = 0; a < 3; ++a)
    EXPECT_NEAR(s.dynamic()->pose(0).translate[size_t(a)], start.translate[size_t(a)] + (*six)[a],
                1e-12);
}

}  // namespace
}  // namespace voxlink::viewer
