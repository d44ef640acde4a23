// SPDX-License-Identifier: BSD-3-Clause
// Hard cases for the GL ray tracer, each held to the float64 reference: rays exactly parallel to
// each axis (zero direction components), the camera inside the volume, rays along brick faces
// and edges, 1-voxel-thick shells, dims that are no multiple of the brick size, a file without
// voxels, a fully occupied volume, and sections split over several buffer textures. No NaN pixel,
// no hang, no missed voxel (a missed opaque voxel would show as a large pixel error).
#include <gtest/gtest.h>

#include <cmath>

#include "render/gl/voxlink_renderer.h"
#include "tests/support/test_util.h"
#include "tests/viewer/gl_test_context.h"
#include "tests/viewer/volume_fixtures.h"

namespace voxlink::render::gl {

namespace {

// A sphere shell one voxel thick in a 37x21x50 volume (no multiple of any brick size) with
// anisotropic spacing; opaque enough that every voxel counts.
struct Scene {
  DenseVolume dense;
  tf::TransferFunction tf;
  voxlink::testing::TempDir dir;
  std::optional<format::VoxLinkFile> file;
  std::unique_ptr<VoxLinkRenderer> renderer;
};

std::unique_ptr<Scene> makeScene(const std::function<double(int, int, int)>& f,
                                 const std::function<bool(double)>& keep, uint32_t brick,
                                 format::Axis axis, const SectionBufferOptions& upload = {}) {
  auto s = std::make_unique<Scene>();
  s->dense = testing::makeVolume({37, 21, 50}, {1.0, 1.3, 0.8}, f);
  s->tf = testing::rampTf(50, 100, 0.9, 50, 255);
  testing::SparseOptions o;
  o.brickSize = brick;
  o.axis = axis;
  auto sparse = testing::sparsify(s->dense, keep, o);
  EXPECT_TRUE(sparse) << sparse.message();
  if (!sparse) return nullptr;
  auto file = testing::writeAndOpen(*sparse, s->dir.file("scene.vxl"));
  EXPECT_TRUE(file) << file.message();
  if (!file) return nullptr;
  s->file.emplace(std::move(*file));
  auto r = VoxLinkRenderer::create(*s->file, upload);
  EXPECT_TRUE(r) << r.message();
  if (!r) return nullptr;
  s->renderer = std::move(*r);
  s->renderer->setTransferFunction(s->tf);
  return s;
}

double shell(int x, int y, int z) {
  const double dx = (x - 18.0) * 1.0, dy = (y - 10.0) * 1.3, dz = (z - 24.5) * 0.8;
  const double r = std::sqrt(dx * dx + dy * dy + dz * dz);
  return std::abs(r - 11.0) < 0.5 ? 220.0 : 0.0;
}

bool positive(double v) { return v > 0; }

RenderSettings smallSettings(Sampling sampling) {
  RenderSettings s;
  s.width = 33;  // odd: the middle column and row of rays run exactly along the view axis
  s.height = 31;
  s.sampling = sampling;
  return s;
}

void expectAgreement(Scene& scene, const Camera& camera, const std::string& what) {
  const ReferenceRenderer reference(scene.dense, scene.tf);
  for (Sampling sampling : {Sampling::kVoxel, Sampling::kTrilinear}) {
    const auto pair =
        testing::renderBoth(*scene.renderer, reference, camera, smallSettings(sampling));
    SCOPED_TRACE(what + ", " + std::string(samplingName(sampling)));
    EXPECT_EQ(pair.error.nonFinite, 0u);
    EXPECT_GE(pair.error.psnr, 45.0);
    EXPECT_LT(pair.error.maxError, 0.05);
  }
}

TEST(HardCases, RaysParallelToEachAxis) {
  VOXLINK_REQUIRE_GL();
  auto scene = makeScene(shell, positive, 8, format::Axis::kY);
  ASSERT_TRUE(scene);
  const Box box = scene->dense.worldBox();
  const glm::dvec3 c = box.center();
  const double far = 3.0 * box.radius();
  for (int axis = 0; axis < 3; ++axis)
    for (double sign : {-1.0, 1.0}) {
      glm::dvec3 eye = c;
      eye[axis] += sign * far;
      const glm::dvec3 up = axis == 2 ? glm::dvec3(0, 1, 0) : glm::dvec3(0, 0, 1);
      expectAgreement(*scene, Camera::lookAt(eye, c, up, 40.0),
                      cat("looking along axis ", axis, " sign ", sign));
    }
}

TEST(HardCases, CameraInsideTheVolume) {
  VOXLINK_REQUIRE_GL();
  auto scene = makeScene(shell, positive, 8, format::Axis::kZ);
  ASSERT_TRUE(scene);
  CameraSpec spec;
  spec.distanceScale = 0.15;  // the eye sits inside the shell
  spec.fovYDeg = 80;
  expectAgreement(*scene, Camera::framing(scene->dense.worldBox(), spec), "eye inside the shell");
  // Exactly at the centre of the box, looking along an axis.
  const glm::dvec3 c = scene->dense.worldBox().center();
  expectAgreement(*scene, Camera::lookAt(c, c + glm::dvec3(0, 0, 1), {0, 1, 0}, 90),
                  "eye at the centre");
}

TEST(HardCases, RaysAlongBrickFacesAndEdges) {
  VOXLINK_REQUIRE_GL();
  // A solid block whose faces lie on brick faces (n = 8): rays run inside those planes.
  auto block = [](int x, int y, int z) {
    return (x >= 8 && x < 24 && y >= 8 && y < 16 && z >= 8 && z < 40) ? 160.0 + (x + y + z) % 40
                                                                      : 0.0;
  };
  auto scene = makeScene(block, positive, 8, format::Axis::kX);
  ASSERT_TRUE(scene);
  const auto& v = scene->dense;
  // World coordinate of index-space plane i along axis a (voxel i spans [i, i + 1)).
  auto plane = [&](int a, double i) { return v.origin[a] + (i - 0.5) * v.spacing[a]; };
  const double zFar = plane(2, 80), zMid = plane(2, 25);
  // The middle ray runs along the face x = 8, then along the edge x = 8, y = 8, then along the
  // face y = 16 (the block's far side), all parallel to z.
  for (auto [x, y] : {std::pair{8.0, 12.0}, std::pair{8.0, 8.0}, std::pair{16.0, 16.0}}) {
    const glm::dvec3 eye(plane(0, x), plane(1, y), zFar), target(plane(0, x), plane(1, y), zMid);
    expectAgreement(*scene, Camera::lookAt(eye, target, {0, 1, 0}, 20.0),
                    cat("along x=", x, " y=", y));
  }
  // Trilinear samples are grouped by dual bricks, whose faces lie half a voxel further, through
  // voxel centres: there a sample sits on the face between two of them.
  for (auto [x, y] : {std::pair{8.5, 12.0}, std::pair{8.5, 8.5}, std::pair{16.5, 16.5}}) {
    const glm::dvec3 eye(plane(0, x), plane(1, y), zFar), target(plane(0, x), plane(1, y), zMid);
    expectAgreement(*scene, Camera::lookAt(eye, target, {0, 1, 0}, 20.0),
                    cat("along x=", x, " y=", y));
  }
  // Diagonally through brick and dual-brick corners.
  for (double i : {0.0, 0.5}) {
    const glm::dvec3 corner(plane(0, 16 + i), plane(1, 8 + i), plane(2, 16 + i));
    expectAgreement(*scene,
                    Camera::lookAt(corner + glm::dvec3(60, 60, 60), corner, {0, 0, 1}, 30.0),
                    cat("through a brick corner + ", i));
  }
}

// Corners of a trilinear cell cross brick faces differently for each brick size and
// predominant axis (the axis along which corners pair up in one row).
TEST(HardCases, EveryBrickSizeAndAxis) {
  VOXLINK_REQUIRE_GL();
  for (uint32_t brick : {4u, 16u, 32u})
    for (format::Axis axis : {format::Axis::kX, format::Axis::kY, format::Axis::kZ}) {
      auto scene = makeScene(shell, positive, brick, axis);
      ASSERT_TRUE(scene);
      CameraSpec spec;
      spec.azimuthDeg = 35;
      spec.elevationDeg = -25;
      expectAgreement(*scene, Camera::framing(scene->dense.worldBox(), spec),
                      cat("brick ", brick, " axis ", static_cast<int>(axis)));
    }
}

TEST(HardCases, EmptyFileRendersTheBackground) {
  VOXLINK_REQUIRE_GL();
  auto scene = makeScene(
      shell, [](double) { return false; }, 8, format::Axis::kZ);
  ASSERT_TRUE(scene);
  EXPECT_EQ(scene->file->voxelCount(), 0u);
  RenderSettings s = smallSettings(Sampling::kTrilinear);
  s.background = {0.2, 0.3, 0.4};
  for (Sampling sampling : {Sampling::kVoxel, Sampling::kTrilinear}) {
    s.sampling = sampling;
    RenderTarget target;
    ASSERT_TRUE(
        scene->renderer->render(Camera::framing(scene->dense.worldBox(), {}), s, target).isOk());
    const Image image = target.read();
    for (size_t i = 0; i < image.rgba.size(); i += 4) {
      ASSERT_EQ(image.rgba[i], 0.2f);
      ASSERT_EQ(image.rgba[i + 1], 0.3f);
      ASSERT_EQ(image.rgba[i + 2], 0.4f);
      ASSERT_EQ(image.rgba[i + 3], 0.0f);
    }
  }
}

TEST(HardCases, FullyOccupiedVolume) {
  VOXLINK_REQUIRE_GL();
  auto smooth = [](int x, int y, int z) {
    return 60.0 + 40.0 * std::sin(0.3 * x) + 0.8 * y + 2.0 * z;
  };
  auto scene = makeScene(
      smooth, [](double) { return true; }, 16, format::Axis::kZ);
  ASSERT_TRUE(scene);
  EXPECT_EQ(scene->file->voxelCount(), scene->dense.voxelCount());
  scene->tf = testing::rampTf(20, 200, 0.08, 20, 220);
  scene->renderer->setTransferFunction(scene->tf);
  expectAgreement(*scene, Camera::framing(scene->dense.worldBox(), {}), "every voxel stored");
}

TEST(HardCases, SplitSectionsRenderTheSameImage) {
  VOXLINK_REQUIRE_GL();
  SectionBufferOptions split;
  split.maxChunkBytes = 4096;
  auto whole = makeScene(shell, positive, 4, format::Axis::kZ);
  auto chunked = makeScene(shell, positive, 4, format::Axis::kZ, split);
  ASSERT_TRUE(whole && chunked);
  EXPECT_GT(chunked->renderer->sections().bindingCount(),
            whole->renderer->sections().bindingCount());
  const Camera camera = Camera::framing(whole->dense.worldBox(), {});
  for (Sampling sampling : {Sampling::kVoxel, Sampling::kTrilinear}) {
    RenderTarget a, b;
    ASSERT_TRUE(whole->renderer->render(camera, smallSettings(sampling), a).isOk());
    ASSERT_TRUE(chunked->renderer->render(camera, smallSettings(sampling), b).isOk());
    EXPECT_EQ(a.read().rgba, b.read().rgba) << samplingName(sampling);
  }
}

// Row groups (the GPU layout of rows with aprons, row_words.h) and row words (llvmpipe's) give
// the same pixels, shadow rays of both kinds included: the shaders read the same rows from either.
TEST(HardCases, RowGroupsRenderTheSameImageAsRowWords) {
  VOXLINK_REQUIRE_GL();
  for (uint32_t brick : {4u, 8u}) {
    SectionBufferOptions groups, words;
    groups.rowGroups = SectionBufferOptions::RowGroups::kOn;
    words.rowGroups = SectionBufferOptions::RowGroups::kOff;
    auto a = makeScene(shell, positive, brick, format::Axis::kY, groups);
    auto b = makeScene(shell, positive, brick, format::Axis::kY, words);
    ASSERT_TRUE(a && b);
    EXPECT_TRUE(a->renderer->sections().rowGroups());
    EXPECT_FALSE(b->renderer->sections().rowGroups());
    EXPECT_LT(a->renderer->gpuBytes(), b->renderer->gpuBytes());
    const Camera camera = Camera::framing(a->dense.worldBox(), {});
    for (Sampling sampling : {Sampling::kVoxel, Sampling::kTrilinear})
      for (int shadows = 0; shadows < 3; ++shadows) {
        RenderSettings s = smallSettings(sampling);
        s.shading.shadows = shadows > 0;
        s.shading.shadowRays = shadows == 2 ? ShadowRays::kPerVoxel : ShadowRays::kPerSample;
        RenderTarget x, y;
        ASSERT_TRUE(a->renderer->render(camera, s, x).isOk());
        ASSERT_TRUE(b->renderer->render(camera, s, y).isOk());
        EXPECT_EQ(x.read().rgba, y.read().rgba)
            << brick << "^3, " << samplingName(sampling) << ", shadows " << shadows;
      }
  }
}

}  // namespace
}  // namespace voxlink::render::gl
