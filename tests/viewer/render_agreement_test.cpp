// SPDX-License-Identifier: BSD-3-Clause
// The GL ray tracer against the float64 reference at default settings: a synthetic shell, and
// real CT (tooth, LIDC chest) converted by the project's converter and rendered with the
// transfer function the file opens with. Target: PSNR >= 45 dB in both sampling modes.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "render/gl/dense_renderer.h"
#include "render/gl/voxlink_renderer.h"
#include "render/recorded_source.h"
#include "tests/support/test_util.h"
#include "tests/viewer/gl_test_context.h"
#include "tests/viewer/volume_fixtures.h"
#include "tf/tf_presets.h"

namespace voxlink::render::gl {

using tf::defaultTransferFunction;

namespace {

constexpr double kTargetPsnr = 45.0;

// Renders the file at default settings in both modes against the reference from its recorded
// source, and the dense peer against the same reference.
void checkFile(const format::VoxLinkFile& file, uint32_t size, const CameraSpec& spec) {
  auto dense = loadSourceVolume(file, "", {});
  ASSERT_TRUE(dense) << dense.message();
  const tf::TransferFunction tf = defaultTransferFunction(file);
  auto renderer = VoxLinkRenderer::create(file);
  ASSERT_TRUE(renderer) << renderer.message();
  (*renderer)->setTransferFunction(tf);
  auto peer = DenseRenderer::create(*dense, (*renderer)->geometry());
  ASSERT_TRUE(peer) << peer.message();
  (*peer)->setTransferFunction(tf);
  const ReferenceRenderer reference(*dense, tf);
  const Camera camera = Camera::framing((*renderer)->geometry().worldBox(), spec);
  for (Sampling sampling : {Sampling::kVoxel, Sampling::kTrilinear}) {
    RenderSettings s;
    s.width = s.height = size;
    s.sampling = sampling;
    const auto sparse = testing::renderBoth(**renderer, reference, camera, s);
    const auto full = testing::renderBoth(**peer, reference, camera, s);
    std::printf("%s %s: voxlink PSNR %.2f dB max %.4f | dense PSNR %.2f dB max %.4f\n",
                file.path().c_str(), std::string(samplingName(sampling)).c_str(), sparse.error.psnr,
                sparse.error.maxError, full.error.psnr, full.error.maxError);
    EXPECT_EQ(sparse.error.nonFinite, 0u);
    EXPECT_GE(sparse.error.psnr, kTargetPsnr) << samplingName(sampling);
    EXPECT_GE(full.error.psnr, kTargetPsnr) << samplingName(sampling);
    // Something must be visible, or the comparison says nothing.
    double coverage = 0;
    for (size_t i = 3; i < sparse.reference.rgba.size(); i += 4)
      coverage += sparse.reference.rgba[i];
    EXPECT_GT(coverage / (size * size), 0.05);
  }
}

TEST(RenderAgreement, SphereShellMatchesReference) {
  VOXLINK_REQUIRE_GL();
  const DenseVolume dense =
      testing::makeVolume({30, 27, 33}, {1.0, 1.2, 0.9}, [](int x, int y, int z) {
        const double r =
            std::sqrt((x - 14.5) * (x - 14.5) + (y - 13.0) * (y - 13.0) + (z - 16.2) * (z - 16.2));
        return std::round(std::clamp(200.0 - 12.0 * std::abs(r - 10.0), 0.0, 255.0));
      });
  auto sparse = testing::sparsify(dense, [](double v) { return v > 100; }, {});
  ASSERT_TRUE(sparse) << sparse.message();
  voxlink::testing::TempDir dir;
  auto file = testing::writeAndOpen(*sparse, dir.file("shell.vxl"));
  ASSERT_TRUE(file) << file.message();
  auto renderer = VoxLinkRenderer::create(*file);
  ASSERT_TRUE(renderer) << renderer.message();
  const tf::TransferFunction tf = testing::rampTf(100, 60, 0.6, 100, 255);
  (*renderer)->setTransferFunction(tf);
  const ReferenceRenderer reference(dense, tf);
  for (Sampling sampling : {Sampling::kVoxel, Sampling::kTrilinear}) {
    RenderSettings s;
    s.width = 96;
    s.height = 80;
    s.sampling = sampling;
    s.shading.shadows = true;
    const auto pair =
        testing::renderBoth(**renderer, reference, Camera::framing(dense.worldBox(), {}), s);
    EXPECT_EQ(pair.error.nonFinite, 0u);
    EXPECT_GE(pair.error.psnr, kTargetPsnr) << samplingName(sampling) << " with shadows";
  }
}

// A ball of 16-bit values first + (x + 2y + 3z) mod count, air (0) around it.
DenseVolume ballOfValues(double first, int count) {
  return testing::makeVolume({20, 18, 22}, {1, 1, 1}, [=](int x, int y, int z) {
    const double r =
        std::sqrt((x - 9.5) * (x - 9.5) + (y - 8.5) * (y - 8.5) + (z - 10.5) * (z - 10.5));
    return r < 8.0 ? first + (x + 2 * y + 3 * z) % count : 0.0;
  });
}

// The u16 VoxLink file of the values >= keepFrom, at `path`.
Result<format::VoxLinkFile> sixteenBitFile(const DenseVolume& dense, double keepFrom,
                                           const std::string& path) {
  testing::SparseOptions options;
  options.type = StoredType::kU16;
  VOXLINK_ASSIGN_OR_RETURN(format::BrickedVolume sparse,
                           testing::sparsify(
                               dense, [=](double v) { return v >= keepFrom; }, options));
  return testing::writeAndOpen(sparse, path);
}

// The unshaded frame (the TF's colours alone) against the reference's.
testing::RenderPair unshaded(VolumeRenderer& renderer, const ReferenceRenderer& reference,
                             const DenseVolume& dense, Sampling sampling) {
  RenderSettings s;
  s.width = 96;
  s.height = 80;
  s.sampling = sampling;
  s.shading.enabled = false;
  return testing::renderBoth(renderer, reference, Camera::framing(dense.worldBox(), {}), s);
}

// A 16-bit file's TF table holds the values the file stores only (VolumeGeometry::firstValueBits):
// colours that alternate from one value to the next would show a table shifted by one entry.
TEST(RenderAgreement, SixteenBitFilesHoldTheTfOfTheirStoredValuesOnly) {
  VOXLINK_REQUIRE_GL();
  const DenseVolume dense = ballOfValues(3000, 8);
  voxlink::testing::TempDir dir;
  auto file = sixteenBitFile(dense, 3000, dir.file("u16.vxl"));
  ASSERT_TRUE(file) << file.message();
  auto renderer = VoxLinkRenderer::create(*file);
  ASSERT_TRUE(renderer) << renderer.message();
  tf::TransferFunction tf;
  tf.opacity = {{2999, 0.0}, {3000, 0.3}, {3007, 0.3}};
  for (int v = 3000; v <= 3007; ++v)
    tf.color.push_back({double(v), v % 2 ? std::array<double, 3>{0.1, 0.3, 1.0}
                                         : std::array<double, 3>{1.0, 0.3, 0.1}});
  (*renderer)->setTransferFunction(tf);
  EXPECT_EQ((*renderer)->geometry().firstValueBits, 3000u);
  EXPECT_EQ((*renderer)->geometry().valueBitsCount, 8u);
  EXPECT_EQ((*renderer)->tfBytes(), 8u * 4u * sizeof(float));  // 8 RGBA floats, not 65,536
  const ReferenceRenderer reference(dense, tf);
  for (Sampling sampling : {Sampling::kVoxel, Sampling::kTrilinear}) {
    const auto pair = unshaded(**renderer, reference, dense, sampling);
    EXPECT_EQ(pair.error.nonFinite, 0u);
    EXPECT_GE(pair.error.psnr, kTargetPsnr) << samplingName(sampling);
  }
}

// The dense peer, given the geometry of a 16-bit VoxLink file, still classifies every source
// value: its texture holds the values the file removed too (values below the file's smallest
// here), which a table of the file's values alone would miss.
TEST(RenderAgreement, DensePeerOfASixteenBitFileHoldsTheWholeTf) {
  VOXLINK_REQUIRE_GL();
  const DenseVolume dense = ballOfValues(1000, 11);
  voxlink::testing::TempDir dir;
  auto file = sixteenBitFile(dense, 1005, dir.file("u16.vxl"));
  ASSERT_TRUE(file) << file.message();
  auto renderer = VoxLinkRenderer::create(*file);
  ASSERT_TRUE(renderer) << renderer.message();
  ASSERT_EQ((*renderer)->geometry().firstValueBits, 1005u);
  auto peer = DenseRenderer::create(dense, (*renderer)->geometry());
  ASSERT_TRUE(peer) << peer.message();
  tf::TransferFunction tf;
  tf.opacity = {{999, 0.0}, {1000, 0.3}, {1010, 0.3}};
  tf.color = {{1000, {1.0, 0.3, 0.1}}, {1010, {0.1, 0.3, 1.0}}};
  (*peer)->setTransferFunction(tf);
  EXPECT_EQ((*peer)->tfBytes(), 65536u * 4u * sizeof(float));
  const ReferenceRenderer reference(dense, tf);
  const auto pair = unshaded(**peer, reference, dense, Sampling::kVoxel);
  EXPECT_EQ(pair.error.nonFinite, 0u);
  EXPECT_GE(pair.error.psnr, kTargetPsnr);
}

TEST(RenderAgreement, ToothCtConvertedByTheConverter) {
  VOXLINK_REQUIRE_DATA("ct/tooth_103x94x161_uint8.raw");
  VOXLINK_REQUIRE_GL();
  voxlink::testing::TempDir dir;
  auto file = testing::convertWithThreshold(testing::toothPath(), testing::toothOpenOptions(),
                                            "121", dir.file("tooth.vxl"));
  ASSERT_TRUE(file) << file.message();
  checkFile(*file, 64, {});
}

TEST(RenderAgreement, LidcChestCt) {
  VOXLINK_REQUIRE_DATA("ct/vtkjs_LIDC2/LIDC2.nhdr");
  VOXLINK_REQUIRE_GL();
  voxlink::testing::TempDir dir;
  auto file = testing::convertWithThreshold(voxlink::testing::dataPath("ct/vtkjs_LIDC2/LIDC2.nhdr"),
                                            {}, "41", dir.file("lidc.vxl"), 8, format::Axis::kY);
  if (!file && file.code() == ErrorCode::kUnsupported)
    GTEST_SKIP() << "no NRRD reader in this build: " << file.message();
  ASSERT_TRUE(file) << file.message();
  checkFile(*file, 64, {});
}

}  // namespace
}  // namespace voxlink::render::gl
