// SPDX-License-Identifier: BSD-3-Clause
// Only what moved, for sphere sets (docs/dynamic-scenes.md, "Moving sphere sets and particles"):
// a set that stands keeps its marks in the sphere lists while another moves, and the frame is
// still the static scene's frozen at that time.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "frozen_scene_frame.h"
#include "gl_test_context.h"
#include "render/camera.h"
#include "render/gl/render_target.h"
#include "render/image.h"
#include "tests/support/test_util.h"
#include "viewer/dynamic_scene.h"

namespace voxlink::viewer {
namespace {

using render::gl::GlDynamicSpheres;

// A floor and a static sphere; 40 particles that move all the time (a 2 s loop) and a gold
// sphere that moves for the first second and stands after it.
std::string writeScene(const ::voxlink::testing::TempDir& dir) {
  std::ofstream(dir.file("floor.obj")) << "v -0.5 0 -0.5\nv -0.5 0 0.5\nv 0.5 0 0.5\nv 0.5 0 -0.5\n"
                                          "f 1 2 3\nf 1 3 4\n";
  std::ofstream particles(dir.file("cluster.txt"));
  for (int i = 0; i < 40; ++i)  // a deterministic scatter (golden-angle spiral)
    particles << 0.12 * std::cos(2.4 * i) << " " << 0.1 + 0.005 * i << " "
              << 0.12 * std::sin(2.4 * i) << " " << 0.01 + 0.001 * i << "\n";
  particles.close();
  const std::string path = dir.file("two-sets.scene.json");
  std::ofstream(path) << R"({"grid": {"resolution": 96, "brick": 8},
    "materials": {"jade": {"color": [0.35, 0.65, 0.45]}, "clay": {"color": [0.8, 0.6, 0.5]},
                  "gold": {"color": [0.9, 0.7, 0.2]}},
    "objects": [
      {"type": "mesh", "file": "floor.obj", "material": "clay"},
      {"type": "sphere", "center": [-0.4, 0.55, -0.4], "radius": 0.05, "material": "clay"},
      {"type": "particles", "file": "cluster.txt", "material": "jade",
       "animation": {"period": 2, "keys": [{"time": 0, "translate": [-0.15, 0, 0]},
                     {"time": 1, "translate": [0.15, 0.05, 0.1], "rotate": [0, 70, 20]}]}},
      {"type": "sphere", "center": [0.3, 0.1, 0.3], "radius": 0.07, "material": "gold",
       "animation": {"keys": [{"time": 0}, {"time": 1, "translate": [-0.2, 0.05, -0.5]}]}}]})";
  return path;
}

render::Image draw(render::gl::VolumeRenderer& renderer, const render::Camera& camera) {
  render::RenderSettings s;
  s.width = s.height = 128;
  s.shading.shadows = true;
  s.shading.lightDirection = {0.6, 1.0, 0.3};
  render::gl::RenderTarget target;
  const Status st = renderer.render(camera, s, target);
  EXPECT_TRUE(st.isOk()) << (st ? "" : st.message());
  return target.read();
}

TEST(DynamicSpheres, AStandingSetKeepsItsMarksWhileAnotherMoves) {
  VOXLINK_REQUIRE_GL();
  ::voxlink::testing::TempDir dir;
  auto description = scene::readSceneDescription(writeScene(dir));
  ASSERT_TRUE(description) << description.message();
  auto dynamic = DynamicScene::load(*description, dir.file("static.vxl"));
  ASSERT_TRUE(dynamic) << dynamic.message();
  DynamicScene& d = **dynamic;
  render::CameraSpec spec;
  spec.azimuthDeg = 30;
  spec.elevationDeg = 35;
  spec.up = render::UpAxis::kY;
  const render::Camera camera = render::Camera::framing(d.renderer().geometry().worldBox(), spec);
  // Per update: the time, then the spheres and sets re-marked and the sets kept. From 1 s the
  // gold sphere stands: at 1.25 s once (not yet two updates), at 1.5 s marked alone and kept,
  // then only the particles; at 0.5 s it moves again (the kept part dropped); the same time
  // again re-marks nothing.
  struct Step {
    double t;
    uint64_t spheres;
    uint32_t sets, kept;
  };
  const std::vector<Step> steps = {{1.0, 41, 2, 0},  {1.25, 41, 2, 0}, {1.5, 41, 2, 1},
                                   {1.75, 40, 1, 1}, {1.9, 40, 1, 1},  {0.5, 41, 2, 0},
                                   {0.5, 0, 0, 0}};
  for (const Step& step : steps) {
    ASSERT_TRUE(d.setTime(step.t).isOk());
    ASSERT_TRUE(d.checkLastUpdate().isOk());
    EXPECT_EQ(d.stats().reVoxelizedSpheres, step.spheres) << "t " << step.t;
    EXPECT_EQ(d.stats().reMarkedSphereSets, step.sets) << "t " << step.t;
    EXPECT_EQ(d.stats().keptSphereSets, step.kept) << "t " << step.t;
    const render::Image frame = draw(d.renderer(), camera);
    const render::Image reference = testing::frozenSceneFrame(
        d, step.t, dir, [&](render::gl::VolumeRenderer& host) { return draw(host, camera); });
    auto e = render::compareImages(frame, reference);
    ASSERT_TRUE(e);
    std::printf(
        "t %.2f: %llu spheres re-marked, %u set(s) kept; vs the static scene: %llu "
        "pixels over 1/255, max error %.4f\n",
        step.t, static_cast<unsigned long long>(d.stats().reVoxelizedSpheres),
        d.stats().keptSphereSets, static_cast<unsigned long long>(e->pixelsOver), e->maxError);
    // The same float spheres and intersection as the static path (DynamicSpheres.Frame*): the
    // same image, whichever sets were kept.
    EXPECT_EQ(e->pixelsOver, 0u) << "t " << step.t;
  }
}

// The lists themselves: a kept sphere stays listed while another is marked, moved and marked
// again on top; a reset without the kept part empties them.
TEST(DynamicSpheres, AKeptPartIsRestoredAndTheOthersMarkedOnTop) {
  VOXLINK_REQUIRE_GL();
  // 8^3 voxels, 2^3 bricks of 4 (index x + 2 y + 4 z): sphere 0 in brick 0, sphere 1 in brick 7.
  auto layer = GlDynamicSpheres::create({8, 8, 8}, {0, 0, 0}, 1.0, 4, 64);
  ASSERT_TRUE(layer) << layer.message();
  layer->reset(false);
  ASSERT_TRUE(layer->mark(0, {{{1, 1, 1}, 0.8f, 0}}).isOk());
  ASSERT_TRUE(layer->keep().isOk());
  EXPECT_TRUE(layer->hasKept());
  ASSERT_TRUE(layer->mark(1, {{{6, 6, 6}, 0.8f, 1}}).isOk());
  auto lists = layer->readLists();
  EXPECT_EQ(lists[0], (std::vector<uint32_t>{0}));
  EXPECT_EQ(lists[7], (std::vector<uint32_t>{1}));
  // Sphere 1 moves to brick 1 (x 4..7): restored kept part, sphere 1 alone marked again.
  layer->reset(true);
  // Index space (voxel i spans [i, i + 1)): the kept sphere's box is voxels 0..2 on each axis.
  EXPECT_EQ(layer->lo(), (std::array<int32_t, 3>{0, 0, 0}));
  EXPECT_EQ(layer->hi(), (std::array<int32_t, 3>{3, 3, 3}));
  ASSERT_TRUE(layer->mark(1, {{{6, 1, 1}, 0.8f, 1}}).isOk());
  ASSERT_TRUE(layer->checkLastUpdate().isOk());
  lists = layer->readLists();
  EXPECT_EQ(lists[0], (std::vector<uint32_t>{0}));
  EXPECT_EQ(lists[1], (std::vector<uint32_t>{1}));
  for (size_t b = 2; b < 8; ++b) EXPECT_TRUE(lists[b].empty()) << b;
  // The ray box covers both: the kept sphere's (x 0..2) and the moved one's (x 5..7).
  EXPECT_EQ(layer->lo(), (std::array<int32_t, 3>{0, 0, 0}));
  EXPECT_EQ(layer->hi(), (std::array<int32_t, 3>{8, 3, 3}));
  // A reset without the kept part: empty lists, the kept part forgotten.
  layer->reset(false);
  EXPECT_FALSE(layer->hasKept());
  lists = layer->readLists();
  for (size_t b = 0; b < 8; ++b) EXPECT_TRUE(lists[b].empty()) << b;
}

}  // namespace
}  // namespace voxlink::viewer
