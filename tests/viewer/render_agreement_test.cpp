// The GL renderers against the float64 reference on small synthetic scenes.
#include <gtest/gtest.h>

#include <cmath>

#include "tests/support/test_util.h"
#include "tests/viewer/gl_test_context.h"
#include "tests/viewer/volume_fixtures.h"
#include "viewer/core/reference_renderer.h"
#include "viewer/gl/voxlink_renderer.h"

namespace voxlink::viewer {
namespace {

using testing::glContext;

TEST(RenderAgreement, SphereShellMatchesReference) {
  VOXLINK_REQUIRE_GL();
  const DenseVolume dense = testing::makeVolume({30, 27, 33}, {1.0, 1.2, 0.9}, [](int x, int y, int z) {
    const double r = std::sqrt((x - 14.5) * (x - 14.5) + (y - 13.0) * (y - 13.0) + (z - 16.2) * (z - 16.2));
    return std::round(std::clamp(200.0 - 12.0 * std::abs(r - 10.0), 0.0, 255.0));
  });
  auto sparse = testing::sparsify(dense, [](double v) { return v > 100; }, {});
  ASSERT_TRUE(sparse) << sparse.message();
  voxlink::testing::TempDir dir;
  auto file = testing::writeAndOpen(*sparse, dir.file("shell.vxl"));
  ASSERT_TRUE(file) << file.message();
  auto renderer = VoxLinkRenderer::create(*file);
  ASSERT_TRUE(renderer) << renderer.message();
  const format::TransferFunction tf = testing::rampTf(100, 60, 0.6, 100, 255);
  (*renderer)->setTransferFunction(tf);
  ReferenceRenderer reference(dense, tf);
  for (Sampling sampling : {Sampling::kVoxel, Sampling::kTrilinear}) {
    RenderSettings s;
    s.width = 96;
    s.height = 80;
    s.sampling = sampling;
    const Camera camera = Camera::framing(dense.worldBox(), CameraSpec{});
    RenderTarget target;
    ASSERT_TRUE((*renderer)->render(camera, s, target).isOk());
    const Image gl = target.read();
    const Image ref = reference.render(camera, s);
    auto e = compareImages(gl, ref);
    ASSERT_TRUE(e);
    EXPECT_EQ(e->nonFinite, 0u);
    EXPECT_GE(e->psnr, 45.0) << samplingName(sampling);
    std::printf("%s: PSNR %.2f dB, max error %.4f\n", std::string(samplingName(sampling)).c_str(), e->psnr, e->maxError);
  }
}

}  // namespace
}  // namespace voxlink::viewer
