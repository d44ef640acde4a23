// SPDX-License-Identifier: BSD-3-Clause
// Per-voxel shadow rays (`--shadow-rays per-voxel`, docs/shadows.md): the GL renderer's per-frame
// cache (shaders/shadow_cache.glsl, filled by shaders/shadow_fill.comp.glsl) against the float64
// reference's per-voxel model on every brick layout, the cache cleared and filled between frames
// where its codes change and reused where they do not, the reference's cache against its uncached
// single rays, and the option.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <tuple>
#include <vector>

#include "render/gl/voxlink_renderer.h"
#include "render/render_options.h"
#include "tests/support/test_util.h"
#include "tests/viewer/gl_test_context.h"
#include "tests/viewer/volume_fixtures.h"
#include "tf/tf_presets.h"

namespace voxlink::render::gl {

namespace {

// A shell of 200 fading over 8 voxels on both sides of radius 10: thick enough to shadow itself.
DenseVolume shell() {
  return testing::makeVolume({30, 27, 33}, {1.0, 1.2, 0.9}, [](int x, int y, int z) {
    const double r =
        std::sqrt((x - 14.5) * (x - 14.5) + (y - 13.0) * (y - 13.0) + (z - 16.2) * (z - 16.2));
    return std::round(std::clamp(200.0 - 12.0 * std::abs(r - 10.0), 0.0, 255.0));
  });
}

RenderSettings shadowed(Sampling sampling, ShadowRays rays) {
  RenderSettings s;
  s.width = 96;
  s.height = 80;
  s.sampling = sampling;
  s.shading.shadows = true;
  s.shading.shadowRays = rays;
  return s;
}

Image renderGl(VolumeRenderer& renderer, const Camera& camera, const RenderSettings& s) {
  RenderTarget target;
  const Status status = renderer.render(camera, s, target);
  EXPECT_TRUE(status.isOk()) << (status ? "" : status.message());
  return target.read();
}

struct Fixture {
  DenseVolume dense = shell();
  tf::TransferFunction tf = testing::rampTf(100, 60, 0.6, 100, 255);
  voxlink::testing::TempDir dir;
  std::optional<format::VoxLinkFile> file;
  std::unique_ptr<VoxLinkRenderer> renderer;

  Status open(const testing::SparseOptions& options = {}) {
    auto sparse = testing::sparsify(
        dense, [](double v) { return v > 100; }, options);
    if (!sparse) return sparse.status();
    VOXLINK_ASSIGN_OR_RETURN(format::VoxLinkFile f,
                             testing::writeAndOpen(*sparse, dir.file("shell.vxl")));
    file.emplace(std::move(f));
    VOXLINK_ASSIGN_OR_RETURN(renderer, VoxLinkRenderer::create(*file));
    renderer->setTransferFunction(tf);
    return Status::ok();
  }
};

// Thresholds: measured 68.1 dB (voxel) and 70.9 dB (trilinear) on llvmpipe (8-bit cached
// transmittances, float32 walks), a few dB below; GL per-sample rays of the same frames measured
// 47.3 and 51.7 dB from the per-voxel reference, so the check tells the two models apart.
TEST(ShadowCache, GlFramesMatchThePerVoxelReference) {
  VOXLINK_REQUIRE_GL();
  Fixture f;
  ASSERT_TRUE(f.open().isOk());
  const ReferenceRenderer reference(f.dense, f.tf);
  const Camera camera = Camera::framing(f.dense.worldBox(), {});
  for (Sampling sampling : {Sampling::kVoxel, Sampling::kTrilinear}) {
    const RenderSettings s = shadowed(sampling, ShadowRays::kPerVoxel);
    const auto cached = testing::renderBoth(*f.renderer, reference, camera, s);
    const Image perSample =
        renderGl(*f.renderer, camera, shadowed(sampling, ShadowRays::kPerSample));
    auto sampleError = compareImages(perSample, cached.reference);
    ASSERT_TRUE(sampleError.isOk());
    std::printf(
        "%s: GL per-voxel vs per-voxel reference %.2f dB (max %.4f); GL per-sample vs "
        "per-voxel reference %.2f dB\n",
        std::string(samplingName(sampling)).c_str(), cached.error.psnr, cached.error.maxError,
        sampleError->psnr);
    EXPECT_EQ(cached.error.nonFinite, 0u);
    EXPECT_GE(cached.error.psnr, sampling == Sampling::kVoxel ? 64.0 : 66.0)
        << samplingName(sampling);
    EXPECT_GT(cached.error.psnr, sampleError->psnr + 10.0) << samplingName(sampling);
  }
}

// Bricks of 4^3 to 32^3 (8^3 and below with row aprons, whose copies have slots of their own;
// 16^3 in row words without them; 32^3 in MASK and ROWS), other predominant axes, and a 16-bit
// file (no apron, values apart from the voxel words).
std::vector<testing::SparseOptions> brickLayouts() {
  std::vector<testing::SparseOptions> layouts;
  for (const auto& [brick, axis, type] : {std::tuple{4u, format::Axis::kZ, StoredType::kU8},
                                          std::tuple{8u, format::Axis::kX, StoredType::kU8},
                                          std::tuple{16u, format::Axis::kY, StoredType::kU8},
                                          std::tuple{32u, format::Axis::kZ, StoredType::kU8},
                                          std::tuple{8u, format::Axis::kZ, StoredType::kU16}}) {
    testing::SparseOptions o;
    o.brickSize = brick;
    o.axis = axis;
    o.type = type;
    layouts.push_back(o);
  }
  return layouts;
}

std::string layoutName(const testing::SparseOptions& o) {
  return cat(o.brickSize, "^3 bricks, axis ", int(o.axis), ", ", storedName(o.type));
}

// The fill pass (shaders/shadow_fill.comp.glsl) finds every visible stored voxel whatever the
// layout (brickLayouts). A voxel it missed would read code 0, far outside [0, 1].
TEST(ShadowCache, FillCoversEveryBrickLayout) {
  VOXLINK_REQUIRE_GL();
  for (const testing::SparseOptions& l : brickLayouts()) {
    Fixture f;
    ASSERT_TRUE(f.open(l).isOk());
    const ReferenceRenderer reference(f.dense, f.tf);
    const Camera camera = Camera::framing(f.dense.worldBox(), {70, 25, 1, 30});
    for (Sampling sampling : {Sampling::kVoxel, Sampling::kTrilinear}) {
      const auto pair = testing::renderBoth(*f.renderer, reference, camera,
                                            shadowed(sampling, ShadowRays::kPerVoxel));
      EXPECT_EQ(pair.error.nonFinite, 0u);
      EXPECT_GE(pair.error.psnr, 64.0) << layoutName(l) << ", " << samplingName(sampling);
    }
  }
}

// The light follows the camera, so a cache left from one view holds the wrong transmittances
// for the next: a second frame from another view equals a fresh renderer's first frame there,
// bit for bit (each cached value is deterministic, whichever invocation computed it).
TEST(ShadowCache, ClearedBetweenFrames) {
  VOXLINK_REQUIRE_GL();
  Fixture first, fresh;
  ASSERT_TRUE(first.open().isOk());
  ASSERT_TRUE(fresh.open().isOk());
  const Camera a = Camera::framing(first.dense.worldBox(), {30, 20, 1, 30});
  const Camera b = Camera::framing(first.dense.worldBox(), {150, -40, 1, 30});
  const uint64_t withoutCache = fresh.renderer->gpuBytes();
  for (Sampling sampling : {Sampling::kVoxel, Sampling::kTrilinear}) {
    const RenderSettings s = shadowed(sampling, ShadowRays::kPerVoxel);
    renderGl(*first.renderer, a, s);
    const Image second = renderGl(*first.renderer, b, s);
    const Image reference = renderGl(*fresh.renderer, b, s);
    auto e = compareImages(second, reference);
    ASSERT_TRUE(e.isOk());
    EXPECT_EQ(e->maxError, 0.0) << samplingName(sampling);
    // The shadows darken the frame, so a stale cache would show.
    RenderSettings unshadowed = s;
    unshadowed.shading.shadows = false;
    auto lit = compareImages(renderGl(*fresh.renderer, b, unshadowed), reference);
    ASSERT_TRUE(lit.isOk());
    EXPECT_LT(lit->psnr, 40.0) << samplingName(sampling);
  }
  // One byte and one mark bit per voxel word (stored voxels and apron copies), in whole words,
  // and the fill pass's 3 words per occupied brick, from the first frame that needs the cache on.
  const uint64_t voxels = fresh.renderer->sections().voxelSlots();
  EXPECT_EQ(fresh.renderer->gpuBytes() - withoutCache,
            (voxels + 3) / 4 * 4 + (voxels + 31) / 32 * 4 + 12 * fresh.file->occupiedBrickCount());
}

// The cache is filled again only where its codes would change: a still frame, a zoom and a pan
// (the light follows the camera's orientation, not its place) and a switch of sampling mode read
// the codes as they are, and equal a fresh renderer's frames bit for bit; a turn, a new transfer
// function, a new shadow stop and forgetShadowCache() fill again.
TEST(ShadowCache, FilledAgainOnlyWhereTheCodesChange) {
  VOXLINK_REQUIRE_GL();
  Fixture kept, fresh;
  ASSERT_TRUE(kept.open().isOk());
  ASSERT_TRUE(fresh.open().isOk());
  // Codes of every visible centre (marked codes hold for one view: MarkedFillRendersTheSameImage).
  kept.renderer->setShadowMarking(VolumeRenderer::ShadowMarking::kOff);
  const Camera start = Camera::framing(kept.dense.worldBox(), {30, 20, 1, 30});
  const RenderSettings voxel = shadowed(Sampling::kVoxel, ShadowRays::kPerVoxel);
  const RenderSettings trilinear = shadowed(Sampling::kTrilinear, ShadowRays::kPerVoxel);
  // Each step: the frame from a renderer whose cache is filled for it alone, a frame of another
  // view there (its cache, bound last, then holds other codes: a kept renderer that read it
  // unbound would show that), then the frame on the kept renderer and whether it filled.
  Camera elsewhere = start;
  elsewhere.orbit(90, 0);
  auto step = [&](const char* what, const Camera& camera, const RenderSettings& s, bool fills) {
    fresh.renderer->forgetShadowCache();
    const Image expected = renderGl(*fresh.renderer, camera, s);
    renderGl(*fresh.renderer, elsewhere, voxel);
    const uint64_t before = kept.renderer->shadowFills();
    const Image image = renderGl(*kept.renderer, camera, s);
    EXPECT_EQ(kept.renderer->shadowFills() - before, fills ? 1u : 0u) << what;
    auto e = compareImages(image, expected);
    ASSERT_TRUE(e.isOk());
    EXPECT_EQ(e->maxError, 0.0) << what;
  };
  step("first frame", start, voxel, true);
  step("still frame", start, voxel, false);
  Camera zoomed = start;
  zoomed.zoom(1.4);
  step("zoom", zoomed, voxel, false);
  Camera panned = zoomed;
  panned.pan(0.1, -0.05);
  step("pan", panned, trilinear, false);
  Camera turned = panned;
  turned.orbit(25, -10);
  step("turn", turned, trilinear, true);
  RenderSettings stop = trilinear;
  stop.shadowTerminationTransmittance = 0.2;
  step("shadow stop", turned, stop, true);
  step("shadow stop back", turned, trilinear, true);
  // A darker TF on both: the codes of the old one would leave too much light.
  const tf::TransferFunction denser = testing::rampTf(100, 60, 0.95, 100, 255);
  kept.renderer->setTransferFunction(denser);
  fresh.renderer->setTransferFunction(denser);
  step("transfer function", turned, trilinear, true);
  kept.renderer->forgetShadowCache();
  step("forgotten", turned, trilinear, true);
  // Frames without per-voxel rays leave the codes alone.
  RenderSettings perSample = trilinear;
  perSample.shading.shadowRays = ShadowRays::kPerSample;
  step("per-sample rays", turned, perSample, false);
  step("per-voxel again", turned, trilinear, false);
}

// The marking frame (shadow_cache.glsl, VXL_SHADOW_MARK) marks every centre the frame reads, so
// a fill of the marked centres alone renders the same image bit for bit as a fill of all visible
// ones, whatever the layout (apron copies included) and sampling, from fewer centres; and marked
// codes hold for their view alone: a still frame reads them, a zoom marks and fills again, while
// codes of every visible voxel serve a marked request from any view.
TEST(ShadowCache, MarkedFillRendersTheSameImage) {
  VOXLINK_REQUIRE_GL();
  for (const testing::SparseOptions& l : brickLayouts()) {
    Fixture f;
    ASSERT_TRUE(f.open(l).isOk());
    const Camera camera = Camera::framing(f.dense.worldBox(), {70, 25, 1, 30});
    for (Sampling sampling : {Sampling::kVoxel, Sampling::kTrilinear}) {
      const RenderSettings s = shadowed(sampling, ShadowRays::kPerVoxel);
      const std::string what = cat(layoutName(l), ", ", samplingName(sampling));
      f.renderer->setShadowMarking(VolumeRenderer::ShadowMarking::kOff);
      f.renderer->forgetShadowCache();
      const Image all = renderGl(*f.renderer, camera, s);
      const uint64_t allCodes = f.renderer->setShadowCodes();
      f.renderer->setShadowMarking(VolumeRenderer::ShadowMarking::kOn);
      f.renderer->forgetShadowCache();
      const uint64_t marks = f.renderer->shadowMarks();
      const Image marked = renderGl(*f.renderer, camera, s);
      EXPECT_EQ(f.renderer->shadowMarks() - marks, 1u);
      // The fill walked fewer centres (the view sees one side of the shell), but some.
      const uint64_t markedCodes = f.renderer->setShadowCodes();
      EXPECT_GT(markedCodes, 0u) << what;
      EXPECT_LT(markedCodes, allCodes) << what;
      auto e = compareImages(marked, all);
      ASSERT_TRUE(e.isOk());
      EXPECT_EQ(e->maxError, 0.0) << what;
    }
  }
  // kAuto marks in voxel sampling where the pixels are fewer than half the voxel slots (without
  // the environment's override).
  unsetenv("VOXLINK_SHADOW_MARK");
  {
    Fixture f;
    ASSERT_TRUE(f.open().isOk());
    const uint64_t slots = f.renderer->sections().voxelSlots();
    const Camera camera = Camera::framing(f.dense.worldBox(), {});
    const uint32_t few = uint32_t(std::sqrt(double(slots) / 4.0));
    const uint32_t many = uint32_t(std::sqrt(double(slots) / 2.0)) + 2;
    ASSERT_GT(few, 8u);
    for (const auto& [sampling, side, marks] :
         {std::tuple{Sampling::kVoxel, few, true}, std::tuple{Sampling::kVoxel, many, false},
          std::tuple{Sampling::kTrilinear, few, false}}) {
      RenderSettings s = shadowed(sampling, ShadowRays::kPerVoxel);
      s.width = s.height = side;
      const uint64_t before = f.renderer->shadowMarks();
      renderGl(*f.renderer, camera, s);
      EXPECT_EQ(f.renderer->shadowMarks() - before, marks ? 1u : 0u)
          << samplingName(sampling) << " " << side << "x" << side << ", " << slots << " slots";
    }
  }
  // Reuse: marked codes cover one view.
  Fixture kept, fresh;
  ASSERT_TRUE(kept.open().isOk());
  ASSERT_TRUE(fresh.open().isOk());
  kept.renderer->setShadowMarking(VolumeRenderer::ShadowMarking::kOn);
  const Camera start = Camera::framing(kept.dense.worldBox(), {30, 20, 1, 30});
  const RenderSettings s = shadowed(Sampling::kTrilinear, ShadowRays::kPerVoxel);
  auto step = [&](const char* what, const Camera& camera, const RenderSettings& settings,
                  bool fills) {
    fresh.renderer->forgetShadowCache();
    const Image expected = renderGl(*fresh.renderer, camera, settings);
    const uint64_t before = kept.renderer->shadowFills();
    const Image image = renderGl(*kept.renderer, camera, settings);
    EXPECT_EQ(kept.renderer->shadowFills() - before, fills ? 1u : 0u) << what;
    auto e = compareImages(image, expected);
    ASSERT_TRUE(e.isOk());
    EXPECT_EQ(e->maxError, 0.0) << what;
  };
  step("first frame", start, s, true);
  step("still frame", start, s, false);
  Camera zoomed = start;
  zoomed.zoom(1.4);
  step("zoom", zoomed, s, true);
  Camera panned = zoomed;
  panned.pan(0.1, -0.05);
  step("pan", panned, s, true);
  RenderSettings voxel = s;
  voxel.sampling = Sampling::kVoxel;
  step("sampling", panned, voxel, true);
  // The same aspect ratio: the camera's uniforms stay, the pixels change.
  RenderSettings larger = voxel;
  larger.width = larger.width * 5 / 4;
  larger.height = larger.height * 5 / 4;
  step("size", panned, larger, true);
  RenderSettings trilinearLarger = larger;
  trilinearLarger.sampling = Sampling::kTrilinear;
  step("sampling back", panned, trilinearLarger, true);
  RenderSettings finer = trilinearLarger;
  finer.stepVoxels = 0.25;
  step("step", panned, finer, true);
  RenderSettings stop = finer;
  stop.terminationAlpha = 0.9;
  step("termination", panned, stop, true);
  step("still again", panned, stop, false);
  // Codes of every visible voxel serve a marked request from any view.
  kept.renderer->setShadowMarking(VolumeRenderer::ShadowMarking::kOff);
  step("unmarked fill", start, s, true);
  kept.renderer->setShadowMarking(VolumeRenderer::ShadowMarking::kOn);
  step("marked request after it", zoomed, s, false);
  step("marked request, another size", zoomed, larger, false);
}

// The reference's per-frame store gives what its uncached single rays compute.
TEST(ShadowCache, ReferenceCacheEqualsUncachedRays) {
  const DenseVolume dense = shell();
  const tf::TransferFunction tf = testing::rampTf(100, 60, 0.6, 100, 255);
  const ReferenceRenderer reference(dense, tf);
  const Camera camera = Camera::framing(dense.worldBox(), {});
  for (Sampling sampling : {Sampling::kVoxel, Sampling::kTrilinear}) {
    RenderSettings s = shadowed(sampling, ShadowRays::kPerVoxel);
    s.width = s.height = 24;
    const Image image = reference.render(camera, s);
    RenderSettings perSample = s;
    perSample.shading.shadowRays = ShadowRays::kPerSample;
    auto differs = compareImages(image, reference.render(camera, perSample));
    ASSERT_TRUE(differs.isOk());
    EXPECT_GT(differs->maxError, 1e-3) << "the models differ";
    for (uint32_t y = 0; y < s.height; y += 5)
      for (uint32_t x = 0; x < s.width; x += 3) {
        const auto pixel = reference.tracePixel(camera, s, x, y);
        for (int c = 0; c < 4; ++c)
          EXPECT_EQ(float(pixel[c]), image.pixel(x, y)[c]) << x << "," << y;
      }
  }
}

TEST(ShadowCache, OptionParses) {
  EXPECT_EQ(parseShadowRays("per-voxel"), ShadowRays::kPerVoxel);
  EXPECT_EQ(parseShadowRays("per-sample"), ShadowRays::kPerSample);
  EXPECT_FALSE(parseShadowRays("voxel"));
  EXPECT_EQ(shadowRaysName(ShadowRays::kPerVoxel), "per-voxel");
  Fixture f;
  auto sparse = testing::sparsify(f.dense, [](double v) { return v > 100; }, {});
  ASSERT_TRUE(sparse);
  auto file = testing::writeAndOpen(*sparse, f.dir.file("shell.vxl"));
  ASSERT_TRUE(file) << file.message();
  RenderOptions o;
  o.shadows = true;
  auto s = o.settings(*file);  // default: per-voxel for a volume file
  ASSERT_TRUE(s) << s.message();
  EXPECT_EQ(s->shading.shadowRays, ShadowRays::kPerVoxel);
  o.shadowRays = "per-sample";
  s = o.settings(*file);
  ASSERT_TRUE(s) << s.message();
  EXPECT_EQ(s->shading.shadowRays, ShadowRays::kPerSample);
  o.shadowRays = "sometimes";
  s = o.settings(*file);
  ASSERT_FALSE(s);
  EXPECT_NE(s.message().find("--shadow-rays"), std::string::npos) << s.message();
}

}  // namespace
}  // namespace voxlink::render::gl
