// SPDX-License-Identifier: BSD-3-Clause
// The float64 reference against closed-form answers, and image metrics.
#include "render/reference_renderer.h"

#include <gtest/gtest.h>

#include <cmath>

#include "render/render_model.h"
#include "tests/viewer/volume_fixtures.h"

namespace voxlink::render {

namespace {

tf::TransferFunction constantTf(double alpha, std::array<double, 3> rgb) {
  tf::TransferFunction tf;
  tf.opacity = {{0, 0.0}, {1, alpha}};
  tf.color = {{0, rgb}};
  return tf;
}

TEST(ReferenceRenderer, UniformSlabMatchesBeerLambert) {
  // Every voxel 1 (opacity 0.2 per unit), unlit: a ray through L units has 1 - 0.8^L opacity.
  const DenseVolume v =
      testing::makeVolume({10, 12, 14}, {1, 1, 1}, [](int, int, int) { return 1.0; });
  const auto tf = constantTf(0.2, {0.5, 0.25, 1.0});
  const ReferenceRenderer ref(v, tf);
  RenderSettings s;
  s.shading.enabled = false;
  s.terminationAlpha = 1.0;
  const Camera c = Camera::lookAt({4.5, 5.5, 50}, {4.5, 5.5, 0}, {0, 1, 0}, 10);
  const Ray ray{{4.5, 5.5, 50}, {0, 0, -1}};
  for (Sampling sampling : {Sampling::kVoxel, Sampling::kTrilinear}) {
    s.sampling = sampling;
    s.stepVoxels = 0.25;
    const auto px = ref.traceRay(ray, c, s);
    // Voxel mode: exact. Trilinear: samples at (k + 1/2) steps over 14 units, all 8 corners
    // inside the volume except within half a voxel of the faces.
    const double exact = 1.0 - std::pow(0.8, 14.0);
    if (sampling == Sampling::kVoxel) {
      EXPECT_NEAR(px[3], exact, 1e-12);
      EXPECT_NEAR(px[0], 0.5 * exact, 1e-12);
    } else {
      EXPECT_NEAR(px[3], 1.0 - std::pow(0.8, 13.0) * std::pow(0.8, 0.5), 0.02);
    }
  }
}

TEST(ReferenceRenderer, MissingTheBoxGivesTheBackground) {
  const DenseVolume v =
      testing::makeVolume({4, 4, 4}, {1, 1, 1}, [](int, int, int) { return 1.0; });
  const auto tf = constantTf(1.0, {1, 1, 1});
  const ReferenceRenderer ref(v, tf);
  RenderSettings s;
  s.background = {0.1, 0.2, 0.3};
  const Camera c = Camera::lookAt({100, 100, 100}, {200, 100, 100}, {0, 0, 1}, 10);
  const auto px = ref.tracePixel(c, s, 0, 0);
  EXPECT_EQ(px[0], 0.1);
  EXPECT_EQ(px[3], 0.0);
}

TEST(RenderModel, BoxIntersectionWithZeroDirectionComponents) {
  const glm::dvec3 lo(0, 0, 0), hi(2, 3, 4);
  auto [t0, t1] = intersectBox({1, 1, -5}, {0, 0, 1}, lo, hi);
  EXPECT_EQ(t0, 5);
  EXPECT_EQ(t1, 9);
  auto miss = intersectBox({5, 1, -5}, {0, 0, 1}, lo, hi);  // parallel, outside the x slab
  EXPECT_GT(miss.first, miss.second);
  auto face = intersectBox({2, 1, -5}, {0, 0, 1}, lo, hi);  // exactly on the face x = 2
  EXPECT_LT(face.first, face.second);
}

TEST(RenderModel, VoxelWalkTilesTheChord) {
  const std::array<uint32_t, 3> dims{7, 5, 9};
  for (const glm::dvec3 d :
       {glm::dvec3(1, 0, 0), glm::dvec3(0.3, -0.5, 0.81), glm::dvec3(0, 0, -1)}) {
    const glm::dvec3 dir = glm::normalize(d);
    const glm::dvec3 o = glm::dvec3(3.5, 2.5, 4.5) - 20.0 * dir;
    auto [t0, t1] = intersectBox(o, dir, glm::dvec3(0), glm::dvec3(7, 5, 9));
    double covered = 0, last = t0;
    int cells = 0;
    walkVoxels(o, dir, t0, t1, dims, [&](const glm::ivec3& c, double a, double b) {
      EXPECT_EQ(a, last);
      EXPECT_GE(b, a);
      EXPECT_TRUE(c.x >= 0 && c.y >= 0 && c.z >= 0 && c.x < 7 && c.y < 5 && c.z < 9);
      covered += b - a;
      last = b;
      ++cells;
      return true;
    });
    EXPECT_NEAR(covered, t1 - t0, 1e-12);
    EXPECT_GT(cells, 0);
  }
}

TEST(RenderModel, ShadingFadesToUnlitWhereNormalsCancel) {
  Shading s;
  const glm::dvec3 c(0.5), light(0, 0, 1), eye(0, 0, 1);
  const auto unlit = shadeSample(c, 1.0, glm::dvec3(0.0), light, eye, s);
  EXPECT_EQ(unlit.ambient, c);
  const auto tiny = shadeSample(c, 1.0, glm::dvec3(0, 0, -1e-9), light, eye, s);
  EXPECT_NEAR(tiny.ambient.x, 0.5, 1e-8);
  EXPECT_NEAR(tiny.lit.x, 0.0, 1e-8);
  const auto facing = shadeSample(c, 1.0, glm::dvec3(0, 0, -1), light, eye, s);
  EXPECT_NEAR(facing.ambient.x, 0.5 * s.ambient, 1e-12);
  EXPECT_NEAR(facing.lit.x, 0.5 * s.diffuse + s.specular, 1e-12);
}

TEST(ImageMetrics, PsnrAndMaxError) {
  Image a(4, 2), b(4, 2);
  EXPECT_TRUE(std::isinf(compareImages(a, b)->psnr));
  b.pixel(1, 1)[0] = 0.5f;
  const auto e = compareImages(a, b);
  ASSERT_TRUE(e);
  EXPECT_EQ(e->maxError, 0.5);
  EXPECT_NEAR(e->psnr, 10 * std::log10(1.0 / (0.25 / 24)), 1e-9);
  EXPECT_EQ(e->pixelsOver, 1u);
  b.pixel(0, 0)[2] = NAN;
  EXPECT_EQ(compareImages(a, b)->nonFinite, 1u);
  EXPECT_EQ(compareImages(a, Image(3, 2)).code(), ErrorCode::kSizeMismatch);
}

}  // namespace
}  // namespace voxlink::render
