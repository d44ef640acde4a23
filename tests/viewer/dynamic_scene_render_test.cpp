// SPDX-License-Identifier: BSD-3-Clause
// A dynamic scene (a static floor, a moving bunny): the frame drawn from the GPU-side dynamic
// layer against the host path for the same frame (`scene build --voxelizer gl` of the scene
// frozen at that time, drawn by VoxLinkRenderer), a pose set directly (a dragged object), and the
// bad inputs it refuses.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <set>

#include "frozen_scene_frame.h"
#include "gl_test_context.h"
#include "render/camera.h"
#include "render/gl/gl_voxelizer.h"
#include "render/gl/render_target.h"
#include "render/image.h"
#include "scene/scene_animation.h"
#include "scene/scene_assembly.h"
#include "tests/support/test_util.h"
#include "viewer/app/detail/object_drag.h"
#include "viewer/dynamic_scene.h"

namespace voxlink::viewer {
namespace {

using namespace render;      // the images and settings a dynamic scene is checked with
using namespace render::gl;  // the renderers and the voxelizer

const char* kMaterials =
    R"({"jade": {"color": [0.35, 0.65, 0.45]}, "clay": {"color": [0.8, 0.6, 0.5]}})";

std::string writeScene(const ::voxlink::testing::TempDir& dir, const std::string& keys,
                       const std::string& materials = kMaterials, int brick = 8) {
  std::ofstream(dir.file("floor.obj")) << "v -0.3 0 -0.3\nv -0.3 0 0.3\nv 0.3 0 0.3\nv 0.3 0 -0.3\n"
                                          "f 1 2 3\nf 1 3 4\n";
  const std::string path = dir.file("moving.scene.json");
  std::ofstream(path) << R"({"grid": {"resolution": 96, "brick": )" + std::to_string(brick) +
                             R"(}, "materials": )" + materials +
                             R"(, "objects": [
      {"type": "mesh", "file": "floor.obj", "material": "clay"},
      {"type": "mesh", "file": ")" +
                             ::voxlink::testing::dataPath("mesh/vtk_bunny.ply") +
                             R"(", "material": "jade", "animation": )" + keys + R"(}]})";
  return path;
}

const char* kKeys = R"({"period": 2, "keys": [{"time": 0, "translate": [-0.1, 0, 0]},
                       {"time": 1, "translate": [0.1, 0, 0.05], "rotate": [0, 60, 0]}]})";

Image renderWith(VolumeRenderer& renderer, const Camera& camera, const RenderSettings& s) {
  RenderTarget target;
  const Status st = renderer.render(camera, s, target);
  EXPECT_TRUE(st.isOk()) << (st ? "" : st.message());
  return target.read();
}

Image renderWith(VolumeRenderer& renderer, const Camera& camera) {
  RenderSettings s;
  s.width = 128;
  s.height = 128;
  return renderWith(renderer, camera, s);
}

// A light from above and the right, so that the bunny casts its shadow on the floor in view.
RenderSettings litFromAbove(bool shadows) {
  RenderSettings s;
  s.width = 128;
  s.height = 128;
  s.shading.shadows = shadows;
  s.shading.lightDirection = {0.6, 1.0, 0.3};
  return s;
}

Image renderLitFromAbove(VolumeRenderer& renderer, const Camera& camera, bool shadows) {
  return renderWith(renderer, camera, litFromAbove(shadows));
}

// The host path's frame: the scene frozen at `t` built by the exact CPU path into a static file,
// drawn by VoxLinkRenderer with the same settings.
Image hostFrame(const DynamicScene& dynamic, double t, const ::voxlink::testing::TempDir& dir,
                const Camera& camera, const RenderSettings& s) {
  return testing::frozenSceneFrame(
      dynamic, t, dir, [&](VolumeRenderer& host) { return renderWith(host, camera, s); });
}

Camera cameraFor(DynamicScene& dynamic) {
  CameraSpec spec;
  spec.azimuthDeg = 30;
  spec.elevationDeg = 35;
  spec.up = UpAxis::kY;
  return Camera::framing(dynamic.renderer().geometry().worldBox(), spec);
}

TEST(DynamicScene, FrameMatchesTheHostPathForTheSameFrame) {
  VOXLINK_REQUIRE_GL();
  ::voxlink::testing::TempDir dir;
  auto description = scene::readSceneDescription(writeScene(dir, kKeys));
  ASSERT_TRUE(description) << description.message();
  auto dynamic = DynamicScene::load(*description, dir.file("static.vxl"));
  ASSERT_TRUE(dynamic) << dynamic.message();
  CameraSpec spec;
  spec.azimuthDeg = 30;
  spec.elevationDeg = 35;
  spec.up = UpAxis::kY;
  const Camera camera = Camera::framing((*dynamic)->renderer().geometry().worldBox(), spec);

  auto voxelizer = GlSurfaceVoxelizer::create();
  ASSERT_TRUE(voxelizer) << voxelizer.message();
  const scene::SurfaceVoxelizer gl =
      [&](const geometry::TriangleMesh& mesh, const geometry::VoxelGrid& grid,
          const std::function<void(double)>&) -> Result<geometry::SurfaceVoxelization> {
    VOXLINK_ASSIGN_OR_RETURN(GlSurfaceVoxelization r, voxelizer->voxelize(mesh, grid));
    return std::move(r.surface);
  };
  Image previous, half;
  for (double t : {0.0, 0.5, 1.0}) {
    ASSERT_TRUE((*dynamic)->setTime(t).isOk());
    ASSERT_TRUE((*dynamic)->layer().checkLastUpdate().isOk());
    const Image frame = renderWith((*dynamic)->renderer(), camera);
    auto built = scene::buildScene((*dynamic)->frozenAt(t), {}, gl);
    ASSERT_TRUE(built) << built.message();
    ASSERT_TRUE(format::writeBrickedVolume(dir.file("frozen.vxl"), built->volume).isOk());
    auto file = format::VoxLinkFile::open(dir.file("frozen.vxl"));
    ASSERT_TRUE(file) << file.message();
    for (int a = 0; a < 3; ++a)
      ASSERT_EQ(file->header().dims[a], (*dynamic)->grid().dims[size_t(a)]);
    auto host = VoxLinkRenderer::create(*file);
    ASSERT_TRUE(host) << host.message();
    const Image reference = renderWith(**host, camera);
    auto e = compareImages(frame, reference);
    ASSERT_TRUE(e);
    std::printf("t %.1f: dynamic layer vs host path %.2f dB, %llu pixels over 1/255\n", t, e->psnr,
                static_cast<unsigned long long>(e->pixelsOver));
    EXPECT_GE(e->psnr, 35.0) << "t " << t;  // measured 39.7-44.6 dB (docs/dynamic-scenes.md)
    EXPECT_EQ(e->nonFinite, 0u);
    if (!previous.rgba.empty()) {  // the bunny moved between the frames
      auto moved = compareImages(frame, previous);
      ASSERT_TRUE(moved);
      EXPECT_LT(moved->psnr, 30.0) << "t " << t;
    }
    previous = frame;
    if (t == 0.5) half = frame;
    if (const char* keep = std::getenv("VOXLINK_KEEP_IMAGES")) {
      (void)writeImage(frame,
                       std::string(keep) + "/dynamic_" + std::to_string(int(t * 10)) + ".png");
      (void)writeImage(reference,
                       std::string(keep) + "/host_" + std::to_string(int(t * 10)) + ".png");
    }
  }
  // Period 2: at 1.5 the loop's way back passes the pose of 0.5.
  ASSERT_TRUE((*dynamic)->setTime(1.5).isOk());
  auto again = compareImages(renderWith((*dynamic)->renderer(), camera), half);
  ASSERT_TRUE(again);
  EXPECT_GE(again->psnr, 60.0);
}

// A file of 16^3 bricks: the layer keeps bricks of 8^3 voxels (viewer/dynamic_scene.cpp) and the
// frame still matches the host path's.
TEST(DynamicScene, AFileOfBigBricksGetsALayerOf8CubedBricks) {
  VOXLINK_REQUIRE_GL();
  ::voxlink::testing::TempDir dir;
  auto description = scene::readSceneDescription(writeScene(dir, kKeys, kMaterials, 16));
  ASSERT_TRUE(description) << description.message();
  auto dynamic = DynamicScene::load(*description, dir.file("static.vxl"));
  ASSERT_TRUE(dynamic) << dynamic.message();
  EXPECT_EQ((*dynamic)->layer().brickSize(), 8u);
  const Camera camera = cameraFor(**dynamic);
  ASSERT_TRUE((*dynamic)->setTime(0.5).isOk());
  ASSERT_TRUE((*dynamic)->layer().checkLastUpdate().isOk());
  RenderSettings s;
  s.width = s.height = 128;
  auto e = compareImages(renderWith((*dynamic)->renderer(), camera, s),
                         hostFrame(**dynamic, 0.5, dir, camera, s));
  ASSERT_TRUE(e);
  std::printf("brick 16 file, t 0.5: dynamic layer vs host path %.2f dB\n", e->psnr);
  EXPECT_GE(e->psnr, 35.0);
}

TEST(DynamicScene, RefusesAnAnimationThatLeavesTheGrid) {
  VOXLINK_REQUIRE_GL();
  ::voxlink::testing::TempDir dir;
  // A key that carries the bunny off the floor's grid.
  auto far = scene::readSceneDescription(
      writeScene(dir, R"({"keys": [{"time": 0}, {"time": 1, "translate": [2, 0, 0]}]})"));
  ASSERT_TRUE(far) << far.message();
  auto loaded = DynamicScene::load(*far, dir.file("static.vxl"));
  ASSERT_FALSE(loaded);
  EXPECT_NE(loaded.message().find("moving.scene.json: objects[1].animation.keys[1]: moves the "
                                  "object outside the grid (x "),
            std::string::npos)
      << loaded.message();
}

// Pixels a shadow darkens: darker with shadows than without by more than 0.05 in green.
std::set<size_t> shadowedPixels(const Image& lit, const Image& unshadowed) {
  std::set<size_t> r;
  for (size_t i = 0; i < size_t(lit.width) * lit.height; ++i)
    if (unshadowed.rgba[4 * i + 1] - lit.rgba[4 * i + 1] > 0.05f) r.insert(i);
  return r;
}

// Shadow rays test the dynamic layer: the frame with shadows matches the host path's for the
// same frame (the scene frozen at that time, its shadows from the static file), and the bunny's
// shadow on the floor moves with it.
TEST(DynamicScene, TheMovingMeshCastsAShadowThatMovesWithIt) {
  VOXLINK_REQUIRE_GL();
  ::voxlink::testing::TempDir dir;
  auto description = scene::readSceneDescription(writeScene(dir, kKeys));
  ASSERT_TRUE(description) << description.message();
  auto dynamic = DynamicScene::load(*description, dir.file("static.vxl"));
  ASSERT_TRUE(dynamic) << dynamic.message();
  const Camera camera = cameraFor(**dynamic);
  std::vector<std::set<size_t>> shadows;
  for (double t : {0.0, 1.0}) {
    ASSERT_TRUE((*dynamic)->setTime(t).isOk());
    ASSERT_TRUE((*dynamic)->layer().checkLastUpdate().isOk());
    const Image frame = renderLitFromAbove((*dynamic)->renderer(), camera, true);
    const Image unshadowed = renderLitFromAbove((*dynamic)->renderer(), camera, false);
    auto e = compareImages(frame, hostFrame(**dynamic, t, dir, camera, litFromAbove(true)));
    ASSERT_TRUE(e);
    shadows.push_back(shadowedPixels(frame, unshadowed));
    std::printf(
        "t %.1f: with shadows, dynamic layer vs host path %.2f dB, %llu pixels over "
        "1/255; %zu pixels shadowed\n",
        t, e->psnr, static_cast<unsigned long long>(e->pixelsOver), shadows.back().size());
    EXPECT_GE(e->psnr, 35.0) << "t " << t;
    EXPECT_GT(shadows.back().size(), 100u) << "t " << t;
  }
  size_t onlyBefore = 0, onlyAfter = 0;
  for (size_t i : shadows[0]) onlyBefore += shadows[1].count(i) == 0;
  for (size_t i : shadows[1]) onlyAfter += shadows[0].count(i) == 0;
  std::printf("shadowed only at 0: %zu pixels, only at 1: %zu\n", onlyBefore, onlyAfter);
  EXPECT_GT(onlyBefore, 50u);
  EXPECT_GT(onlyAfter, 50u);
}

// The ray-traced mode's rays test the dynamic layer: a mirror floor shows the moving bunny, whose
// glass refracts; the frame matches the host path's for the same frame.
TEST(DynamicScene, TheRayTracedModeSeesTheMovingMesh) {
  VOXLINK_REQUIRE_GL();
  ::voxlink::testing::TempDir dir;
  auto description = scene::readSceneDescription(
      writeScene(dir, kKeys,
                 R"({"jade": {"color": [0.35, 0.65, 0.45], "reflectivity": 0.2, "transmission": 0.4,
                   "ior": 1.3},
          "clay": {"color": [0.8, 0.6, 0.5], "reflectivity": 0.5}})"));
  ASSERT_TRUE(description) << description.message();
  auto dynamic = DynamicScene::load(*description, dir.file("static.vxl"));
  ASSERT_TRUE(dynamic) << dynamic.message();
  const Camera camera = cameraFor(**dynamic);
  RenderSettings s = litFromAbove(true);
  s.effects.reflect = s.effects.refract = s.effects.shadows = true;
  Image previous;
  for (double t : {0.0, 1.0}) {
    ASSERT_TRUE((*dynamic)->setTime(t).isOk());
    const Image frame = renderWith((*dynamic)->renderer(), camera, s);
    ASSERT_TRUE((*dynamic)->layer().checkLastUpdate().isOk());
    auto e = compareImages(frame, hostFrame(**dynamic, t, dir, camera, s));
    ASSERT_TRUE(e);
    auto plain = compareImages(frame, renderLitFromAbove((*dynamic)->renderer(), camera, true));
    ASSERT_TRUE(plain);
    std::printf(
        "t %.1f: ray-traced, dynamic layer vs host path %.2f dB, %llu pixels over 1/255; "
        "vs the plain frame %.2f dB\n",
        t, e->psnr, static_cast<unsigned long long>(e->pixelsOver), plain->psnr);
    EXPECT_GE(e->psnr, 35.0) << "t " << t;
    EXPECT_LT(plain->psnr, 35.0) << "t " << t;  // the mirror and the glass show
    if (!previous.rgba.empty()) {
      auto moved = compareImages(frame, previous);
      ASSERT_TRUE(moved);
      EXPECT_LT(moved->psnr, 30.0);
    }
    previous = frame;
  }
}

}  // namespace
}  // namespace voxlink::viewer

namespace voxlink::viewer {
namespace {

using namespace render;      // the images and settings a dynamic scene is checked with
using namespace render::gl;  // the renderers and the voxelizer

std::set<uint64_t> keysOf(const GlDynamicLayer& layer) {
  std::set<uint64_t> keys;
  for (const auto& v : layer.readVoxels()) keys.insert(v.first);
  return keys;
}

// What the viewer does when the user drags the bunny: setPose() with a translation, clamped
// into the grid by viewer::clampTranslation first.
TEST(DynamicScene, ASetPoseGivesTheMovedVoxelsAndStaysInTheGrid) {
  VOXLINK_REQUIRE_GL();
  ::voxlink::testing::TempDir dir;
  auto description = scene::readSceneDescription(writeScene(dir, R"({"keys": [{"time": 0}]})"));
  ASSERT_TRUE(description) << description.message();
  auto dynamic = DynamicScene::load(*description, dir.file("static.vxl"));
  ASSERT_TRUE(dynamic) << dynamic.message();
  DynamicScene& d = **dynamic;
  const auto objects = d.movingObjects();
  ASSERT_EQ(objects.size(), 1u);
  EXPECT_EQ(objects[0].object, 1u);
  ASSERT_TRUE(d.setTime(0).isOk());
  const std::set<uint64_t> rest = keysOf(d.layer());
  ASSERT_GT(rest.size(), 100u);

  // By whole voxels: the rest voxels moved by as many.
  const double s = d.grid().spacing;
  scene::Pose pose;
  pose.translate = {3 * s, -2 * s, 1 * s};
  ASSERT_TRUE(d.setPose(0, pose).isOk());
  ASSERT_TRUE(d.layer().checkLastUpdate().isOk());
  std::set<uint64_t> expected;
  for (uint64_t key : rest) {
    const auto v = geometry::voxelFromKey(key);
    expected.insert(geometry::voxelKey(v[0] + 3, v[1] - 2, v[2] + 1));
  }
  EXPECT_EQ(keysOf(d.layer()), expected);
  EXPECT_EQ(d.pose(0).translate, pose.translate);

  // Dragged far along +x: clamped to the grid's face, accepted, reaching the last column.
  const geometry::Bounds3& b = objects[0].restBounds;
  const geometry::Bounds3 grid = scene::gridBox(d.grid());
  const Box restBox{{b.min[0], b.min[1], b.min[2]}, {b.max[0], b.max[1], b.max[2]}};
  const Box limits{{grid.min[0], grid.min[1], grid.min[2]},
                   {grid.max[0], grid.max[1], grid.max[2]}};
  auto clamped = viewer::clampTranslation(restBox, {1e3, 0, 0}, limits);
  ASSERT_TRUE(clamped) << clamped.message();
  EXPECT_EQ(clamped->clamped, (std::array<bool, 3>{true, false, false}));
  pose.translate = {clamped->translation.x, clamped->translation.y, clamped->translation.z};
  const Status atFace = d.setPose(0, pose);
  ASSERT_TRUE(atFace.isOk()) << atFace.message();
  const std::set<uint64_t> atFaceKeys = keysOf(d.layer());
  uint32_t maxX = 0;
  for (uint64_t key : atFaceKeys) maxX = std::max(maxX, geometry::voxelFromKey(key)[0]);
  EXPECT_EQ(maxX, d.grid().dims[0] - 1);

  // A voxel further: refused in one line, the last frame kept.
  pose.translate[0] += s;
  const Status outside = d.setPose(0, pose);
  ASSERT_FALSE(outside.isOk());
  EXPECT_NE(outside.message().find(
                "moving.scene.json: objects[1]: the pose moves the object outside the grid (x "),
            std::string::npos)
      << outside.message();
  EXPECT_EQ(keysOf(d.layer()), atFaceKeys);
  EXPECT_FALSE(d.setPose(1, {}).isOk());  // only one object moves
  scene::Pose notFinite;
  notFinite.rotateDegrees[1] = std::nan("");
  EXPECT_FALSE(d.setPose(0, notFinite).isOk());
}

// A pool split over three storage buffers (a test cap on bytes per buffer, as a pool over
// GL_MAX_SHADER_STORAGE_BLOCK_SIZE is split) draws the frame one buffer draws, bit for bit.
TEST(DynamicScene, APoolSplitOverBuffersDrawsTheSameFrame) {
  VOXLINK_REQUIRE_GL();
  ::voxlink::testing::TempDir dir;
  auto description = scene::readSceneDescription(writeScene(dir, kKeys));
  ASSERT_TRUE(description) << description.message();
  auto prepared = DynamicScene::prepare(*description, dir.file("static.vxl"));
  ASSERT_TRUE(prepared) << prepared.message();
  DynamicScene::Prepared split = *prepared;
  split.poolBufferBytes = (prepared->bricks + 2) / 3 * prepared->brick * prepared->brick *
                          prepared->brick * 16;  // 16 bytes per voxel
  auto one = DynamicScene::load(std::move(*prepared));
  ASSERT_TRUE(one) << one.message();
  auto three = DynamicScene::load(std::move(split));
  ASSERT_TRUE(three) << three.message();
  EXPECT_EQ((*one)->layer().poolBuffers(), 1u);
  EXPECT_EQ((*three)->layer().poolBuffers(), 3u);
  const Camera camera = cameraFor(**one);
  for (double t : {0.0, 0.5, 1.3}) {
    ASSERT_TRUE((*one)->setTime(t).isOk());
    ASSERT_TRUE((*three)->setTime(t).isOk());
    ASSERT_TRUE((*one)->checkLastUpdate().isOk());
    ASSERT_TRUE((*three)->checkLastUpdate().isOk());
    EXPECT_EQ((*one)->layer().readVoxels(), (*three)->layer().readVoxels()) << "t " << t;
    const Image a = renderLitFromAbove((*one)->renderer(), camera, true);
    const Image b = renderLitFromAbove((*three)->renderer(), camera, true);
    ASSERT_EQ(a.rgba.size(), b.rgba.size());
    size_t differing = 0, covered = 0;
    for (size_t i = 0; i < a.rgba.size(); ++i) differing += a.rgba[i] != b.rgba[i];
    for (size_t i = 3; i < a.rgba.size(); i += 4) covered += a.rgba[i] > 0;
    EXPECT_EQ(differing, 0u) << "t " << t;
    EXPECT_GT(covered, a.rgba.size() / 40) << "t " << t;  // not an empty frame
  }
}

}  // namespace
}  // namespace voxlink::viewer
