// SPDX-License-Identifier: BSD-3-Clause
// Moving sphere sets at their edges (docs/dynamic-scenes.md): one sphere, a sphere nearly as
// large as the grid, a sphere touching the grid's side, a dozen sphere sets moving over a
// standing floor; 4^3 and 16^3 bricks at 64 and 128. Each frame must be the static scene's with
// the spheres at that pose (the scene frozen at that time), as DynamicSpheres.* check.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <string>

#include "format/bricked_volume.h"
#include "frozen_scene_frame.h"
#include "gl_test_context.h"
#include "render/camera.h"
#include "render/gl/render_target.h"
#include "render/gl/voxlink_renderer.h"
#include "render/image.h"
#include "scene/scene_assembly.h"
#include "tests/support/test_util.h"
#include "viewer/dynamic_scene.h"

namespace voxlink::viewer {
namespace {

using namespace render;
using namespace render::gl;

Image draw(VolumeRenderer& renderer, const Camera& camera) {
  RenderSettings s;
  s.width = 96;
  s.height = 96;
  s.shading.lightDirection = {0.6, 1.0, 0.3};
  RenderTarget target;
  const Status st = renderer.render(camera, s, target);
  EXPECT_TRUE(st.isOk()) << (st ? "" : st.message());
  return target.read();
}

// A floor of half-width `extent` and two small static spheres at opposite corners (the grid
// holds the motion), then `moving`.
std::string writeScene(const ::voxlink::testing::TempDir& dir, int resolution, int brick,
                       double extent, const std::string& moving) {
  std::ofstream(dir.file("floor.obj")) << "v -1 0 -1\nv -1 0 1\nv 1 0 1\nv 1 0 -1\nf 1 2 3 4\n";
  std::ofstream(dir.file("one.txt")) << "0 0.1 0 0.05\n";
  const std::string e = std::to_string(extent);
  const std::string path = dir.file("edges.scene.json");
  std::ofstream(path) << "{\"grid\": {\"resolution\": " << resolution << ", \"brick\": " << brick
                      << R"(}, "materials": {"jade": {"color": [0.35, 0.65, 0.45]},
      "clay": {"color": [0.8, 0.6, 0.5]}},
    "objects": [
      {"type": "mesh", "file": "floor.obj", "material": "clay",
       "transform": {"scale": [)"
                      << e << ", 1, " << e << R"(]}},
      {"type": "sphere", "center": [-)"
                      << e << ", " << e << ", -" << e << R"(], "radius": 0.05, "material": "clay"},
      {"type": "sphere", "center": [)"
                      << e << ", -" << e << ", " << e << R"(], "radius": 0.05, "material": "clay"},
      )" << moving << "]}";
  return path;
}

const char* kMove =
    R"("animation": {"period": 2, "keys": [{"time": 0, "translate": [-0.05, 0, 0]},
       {"time": 1, "translate": [0.05, 0.02, 0.03]}]})";

void expectStaticFrames(const std::string& what, double extent, const std::string& moving) {
  for (int resolution : {64, 128})
    for (int brick : {4, 16}) {
      SCOPED_TRACE(what + " resolution " + std::to_string(resolution) + " brick " +
                   std::to_string(brick));
      ::voxlink::testing::TempDir dir;
      auto description =
          scene::readSceneDescription(writeScene(dir, resolution, brick, extent, moving));
      ASSERT_TRUE(description) << description.message();
      auto dynamic = DynamicScene::load(*description, dir.file("static.vxl"));
      ASSERT_TRUE(dynamic) << dynamic.message();
      DynamicScene& d = **dynamic;
      CameraSpec spec;
      spec.azimuthDeg = 30;
      spec.elevationDeg = 35;
      spec.up = UpAxis::kY;
      const Camera camera = Camera::framing(d.renderer().geometry().worldBox(), spec);
      for (double t : {0.0, 0.3, 1.0, 1.5, 0.0}) {
        ASSERT_TRUE(d.setTime(t).isOk());
        ASSERT_TRUE(d.checkLastUpdate().isOk());
        const Image frame = draw(d.renderer(), camera);
        auto e = compareImages(
            frame, testing::frozenSceneFrame(
                       d, t, dir, [&](VolumeRenderer& host) { return draw(host, camera); }));
        ASSERT_TRUE(e);
        EXPECT_EQ(e->pixelsOver, 0u) << "t " << t << ": max error " << e->maxError;
      }
    }
}

TEST(DynamicSpheresEdges, OneSphereAndOneParticle) {
  VOXLINK_REQUIRE_GL();
  expectStaticFrames("one sphere", 0.6,
                     std::string(R"({"type": "sphere", "center": [0, 0.2, 0], "radius": 0.1,
                                     "material": "jade", )") +
                         kMove + "}");
  expectStaticFrames("one particle", 0.6,
                     std::string(R"({"type": "particles", "file": "one.txt", "material": "jade",
                                     )") +
                         kMove + "}");
}

TEST(DynamicSpheresEdges, ASphereNearlyAsLargeAsTheGridAndOneAtItsSide) {
  VOXLINK_REQUIRE_GL();
  expectStaticFrames("huge", 6,
                     std::string(R"({"type": "sphere", "center": [0, 0, 0], "radius": 5.9,
                                     "material": "jade", )") +
                         kMove + "}");
  expectStaticFrames("at the side", 0.9,
                     std::string(R"({"type": "sphere", "center": [0.45, 0.2, 0], "radius": 0.4,
                                     "material": "jade", )") +
                         kMove + "}");
}

TEST(DynamicSpheresEdges, ADozenSphereSetsOverAStandingFloor) {
  VOXLINK_REQUIRE_GL();
  std::string sets;
  for (int i = 0; i < 12; ++i)
    sets += std::string(i ? ", " : "") + R"({"type": "sphere", "center": [)" +
            std::to_string(-0.5 + 0.09 * i) + ", " + std::to_string(0.05 + 0.04 * i) +
            ", 0], \"radius\": " + std::to_string(0.02 + 0.01 * (i % 4)) +
            R"(, "material": "jade", )" + kMove + "}";
  expectStaticFrames("dozen", 0.8, sets);
}

// A moving mesh and moving spheres with the mesh layer's pool split over four storage buffers
// (the test cap on bytes per buffer): the plain frame with shadows and the ray-traced frame
// (reflections, shadows) equal one buffer's bit for bit; the tracer then declares every pool
// buffer beside the sphere lists.
TEST(DynamicSpheresEdges, FourPoolBuffersBesideMovingSpheresDrawOneBuffersFrames) {
  VOXLINK_REQUIRE_GL();
  ::voxlink::testing::TempDir dir;
  const std::string moving =
      std::string(R"({"type": "sphere", "center": [0.1, 0.3, 0], "radius": 0.15,
                      "material": "jade", )") +
      kMove + R"(}, {"type": "mesh", "file": "floor.obj", "material": "jade",
      "transform": {"scale": [0.3, 1, 0.3], "rotate": [0, 0, 60], "translate": [-0.2, 0.2, 0]},
      )" +
      kMove + "}";
  auto description = scene::readSceneDescription(writeScene(dir, 96, 8, 0.6, moving));
  ASSERT_TRUE(description) << description.message();
  auto prepared = DynamicScene::prepare(*description, dir.file("static.vxl"));
  ASSERT_TRUE(prepared) << prepared.message();
  DynamicScene::Prepared split = *prepared;
  split.poolBufferBytes = (prepared->bricks + 3) / 4 * 8 * 8 * 8 * 16;  // 16 bytes per voxel
  auto one = DynamicScene::load(std::move(*prepared));
  ASSERT_TRUE(one) << one.message();
  auto four = DynamicScene::load(std::move(split));
  ASSERT_TRUE(four) << four.message();
  EXPECT_EQ((*one)->layer().poolBuffers(), 1u);
  EXPECT_EQ((*four)->layer().poolBuffers(), 4u);
  CameraSpec spec;
  spec.azimuthDeg = 30;
  spec.elevationDeg = 35;
  spec.up = UpAxis::kY;
  const Camera camera = Camera::framing((*one)->renderer().geometry().worldBox(), spec);
  RenderSettings s;
  s.width = s.height = 64;
  s.shading.shadows = true;
  s.shading.lightDirection = {0.6, 1.0, 0.3};
  for (bool effects : {false, true}) {
    s.effects.reflect = s.effects.shadows = effects;
    for (double t : {0.3, 1.0}) {
      ASSERT_TRUE((*one)->setTime(t).isOk());
      ASSERT_TRUE((*four)->setTime(t).isOk());
      ASSERT_TRUE((*one)->checkLastUpdate().isOk());
      ASSERT_TRUE((*four)->checkLastUpdate().isOk());
      RenderTarget a, b;
      const Status ra = (*one)->renderer().render(camera, s, a);
      const Status rb = (*four)->renderer().render(camera, s, b);
      ASSERT_TRUE(ra.isOk()) << ra.message();
      ASSERT_TRUE(rb.isOk()) << rb.message();
      auto e = compareImages(a.read(), b.read());
      ASSERT_TRUE(e);
      EXPECT_EQ(e->pixelsOver, 0u) << "effects " << effects << " t " << t;
      EXPECT_EQ(e->maxError, 0.0) << "effects " << effects << " t " << t;
    }
  }
}

}  // namespace
}  // namespace voxlink::viewer
