// SPDX-License-Identifier: BSD-3-Clause
// Moving sphere sets in the viewer (docs/dynamic-scenes.md, "In the viewer"): a Ctrl press on
// static particles makes them move (SceneSession::promote through DragGesture), the frame at rest
// is the frame of the scene where they move from the start, and the motion that follows drags
// them, re-marking their spheres (headless EGL, 128x128).
#include <gtest/gtest.h>

#include <cmath>
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

// objects: 0 a floor, 1 a cluster of 30 particles, 2 a static sphere; nothing moves.
std::string writeScene(const ::voxlink::testing::TempDir& dir) {
  std::ofstream(dir.file("floor.obj")) << "v -0.3 0 -0.3\nv -0.3 0 0.3\nv 0.3 0 0.3\nv 0.3 0 -0.3\n"
                                          "f 1 2 3\nf 1 3 4\n";
  std::ofstream particles(dir.file("cluster.txt"));
  for (int i = 0; i < 30; ++i)
    particles << 0.08 * std::cos(2.4 * i) << " " << 0.06 + 0.004 * i << " "
              << 0.08 * std::sin(2.4 * i) << " " << 0.02 + 0.001 * i << "\n";
  particles.close();
  const std::string path = dir.file("particles.scene.json");
  std::ofstream(path) << R"({"grid": {"resolution": 64, "brick": 8},
    "materials": {"jade": {"color": [0.35, 0.65, 0.45]}, "clay": {"color": [0.8, 0.6, 0.5]}},
    "objects": [
      {"type": "mesh", "file": "floor.obj", "material": "clay"},
      {"type": "particles", "file": "cluster.txt", "material": "jade"},
      {"type": "sphere", "center": [-0.2, 0.05, -0.2], "radius": 0.04, "material": "clay"}],
    "camera": {"azimuth": 30, "elevation": 35, "up": "y"}})";
  return path;
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

render::Image sessionFrame(SceneSession& s) {
  ViewerState state;
  EXPECT_TRUE(state.load(s.volumeFile(), false, s.renderer()).isOk());
  return state.file ? frameOf(*state.renderer, *state.file) : render::Image{};
}

TEST(SpherePromotion, ACtrlPressOnStaticParticlesMakesThemMoveAndDragsThem) {
  VOXLINK_REQUIRE_GL();
  ::voxlink::testing::TempDir dir;
  const std::string path = writeScene(dir);
  auto session = SceneSession::prepare(path, {});
  ASSERT_TRUE(session) << session.message();
  SceneSession& s = **session;
  ASSERT_TRUE(s.attach().isOk());
  EXPECT_FALSE(s.moves());
  ASSERT_EQ(s.staticObjects().size(), 3u);  // floor, particles, sphere
  EXPECT_EQ(s.objectName(1), "objects[1] cluster.txt");
  EXPECT_EQ(s.objectName(2), "objects[2] sphere");  // no file: its kind

  auto file = format::VoxLinkFile::open(s.volumeFile());
  ASSERT_TRUE(file);
  render::CameraSpec spec;
  spec.azimuthDeg = 30;
  spec.elevationDeg = 35;
  spec.up = render::UpAxis::kY;
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
  // A pixel whose nearest static box is the particles' (object 1).
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
  EXPECT_TRUE(step(true, 0));  // pressed: the particles are being made to move
  EXPECT_TRUE(drag.holding());
  EXPECT_FALSE(drag.active());
  ASSERT_TRUE(s.promoting().has_value());
  EXPECT_EQ(s.promoting()->first, 1u);
  ASSERT_TRUE(s.finishPromotion().isOk());
  ASSERT_TRUE(s.moves());
  const auto index = s.movingIndexOf(1);
  ASSERT_TRUE(index.has_value());
  EXPECT_EQ(s.movingName(*index), "objects[1] cluster.txt");
  auto updated = s.update(0);
  ASSERT_TRUE(updated && *updated);
  EXPECT_EQ(s.dynamic()->stats().reVoxelizedSpheres, 30u);
  const render::Image atRest = sessionFrame(s);

  // The scene where the particles move from the start (one key at rest), as `view` shows it.
  ::voxlink::testing::TempDir other;
  auto fresh = scene::readSceneDescription(writeScene(other));
  ASSERT_TRUE(fresh);
  fresh->objects[1].animation = scene::Animation{{scene::AnimationKey{}}, 0};
  auto dynamic = DynamicScene::load(*fresh, other.file("fresh.vxl"));
  ASSERT_TRUE(dynamic) << dynamic.message();
  ASSERT_TRUE((*dynamic)->setTime(0).isOk());
  ViewerState freshState;
  ASSERT_TRUE(freshState.load(other.file("fresh.vxl"), false, &(*dynamic)->renderer()).isOk());
  const render::Image want = frameOf(*freshState.renderer, *freshState.file);
  ASSERT_EQ(atRest.rgba.size(), want.rgba.size());
  EXPECT_TRUE(atRest.rgba == want.rgba);  // bit for bit
  size_t green = 0;                       // the particles show (jade where lit)
  for (size_t i = 0; i < atRest.rgba.size(); i += 4)
    green += atRest.rgba[i + 1] > 1.2f * atRest.rgba[i] && atRest.rgba[i + 3] > 0.5f;
  EXPECT_GT(green, 50u);

  EXPECT_TRUE(step(true, 6));  // swapped in: the drag starts from the press
  EXPECT_TRUE(drag.active());
  ASSERT_TRUE(s.dragging().has_value());
  EXPECT_EQ(*s.dragging(), *index);
  updated = s.update(0);
  ASSERT_TRUE(updated && *updated);
  const scene::Pose& pose = s.dynamic()->pose(*index);
  EXPECT_GT(std::abs(pose.translate[0]) + std::abs(pose.translate[1]) + std::abs(pose.translate[2]),
            1e-3);
  EXPECT_EQ(s.dynamic()->stats().reVoxelizedSpheres, 30u);
  ASSERT_TRUE(s.dynamic()->checkLastUpdate().isOk());
  auto moved = compareImages(sessionFrame(s), atRest);
  ASSERT_TRUE(moved);
  EXPECT_GT(moved->pixelsOver, 20u);  // the cluster moved in the image
  EXPECT_FALSE(step(false, 6));
  EXPECT_TRUE(s.held(*index));  // stays where it was dragged
  updated = s.update(0.1);      // held, nothing moved: nothing re-marked
  ASSERT_TRUE(updated);
  EXPECT_EQ(s.dynamic()->stats().reVoxelizedSpheres, 0u);
}

}  // namespace
}  // namespace voxlink::viewer
