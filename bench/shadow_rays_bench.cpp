// SPDX-License-Identifier: BSD-3-Clause
// Shadow rays, speed against error (docs/shadows.md): for one file and sampling mode, the GL
// frame without shadows, with per-sample shadow rays, with per-voxel ones (the cache, filled
// for the view) and the per-voxel frame again from the same view (a still frame: the cache as
// it is), interleaved view by view over the paper's protocol (a turn about y, then one about x),
// so that a load change on a shared machine hits the four alike; median frame times and their
// ratios; PSNR of each frame against both float64 references (per-sample and per-voxel rays) at
// the first view, and of the per-voxel reference against the per-sample one (the model's own
// error, free of any GL-vs-reference difference). Prints one markdown table row.
//
// usage: voxlink_bench_shadow_rays NAME FILE.vxl TF.json voxel|trilinear WxH FRAMES_PER_TURN
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "render/gl/gl_context.h"
#include "render/gl/render_benchmark.h"
#include "render/gl/voxlink_renderer.h"
#include "render/recorded_source.h"
#include "render/reference_renderer.h"

namespace {

using namespace voxlink;
using namespace voxlink::render;

double seconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

int fail(const std::string& what) {
  std::fprintf(stderr, "voxlink_bench_shadow_rays: %s\n", what.c_str());
  return 1;
}

int run(int argc, char** argv) {
  if (argc != 7) return fail("usage: NAME FILE.vxl TF.json voxel|trilinear WxH FRAMES_PER_TURN");
  const std::string name = argv[1];
  auto file = format::VoxLinkFile::open(argv[2]);
  if (!file) return fail(file.message());
  auto tf = tf::loadTransferFunction(argv[3]);
  if (!tf) return fail(tf.message());
  const auto sampling = parseSampling(argv[4]);
  if (!sampling) return fail(std::string("sampling: '") + argv[4] + "' is not voxel or trilinear");
  auto size = parseImageSize(argv[5]);
  if (!size) return fail(size.message());
  const int perTurn = std::atoi(argv[6]);
  if (perTurn < 1) return fail(std::string("frames per turn: '") + argv[6] + "' is not >= 1");
  auto dense = loadSourceVolume(*file, "", {});
  if (!dense) return fail(dense.message());
  auto context = gl::createHeadlessContext();
  if (!context) return fail(context.message());
  auto renderer = gl::VoxLinkRenderer::create(*file);
  if (!renderer) return fail(renderer.message());
  (*renderer)->setTransferFunction(*tf);
  const uint64_t plainBytes = (*renderer)->gpuBytes();

  RenderSettings none;
  none.width = (*size)[0];
  none.height = (*size)[1];
  none.sampling = *sampling;
  RenderSettings perSample = none, perVoxel = none;
  perSample.shading.shadows = perVoxel.shading.shadows = true;
  perSample.shading.shadowRays = ShadowRays::kPerSample;
  perVoxel.shading.shadowRays = ShadowRays::kPerVoxel;
  const std::vector<RenderSettings> variants{none, perSample, perVoxel};

  const Camera start = Camera::framing((*renderer)->geometry().worldBox(), {});
  gl::RenderTarget target;
  std::vector<Image> first;
  for (const RenderSettings& s : variants) {  // warm-up (compiles, JIT); its frame is view 0
    if (Status st = (*renderer)->render(start, s, target); !st) return fail(st.message());
    first.push_back(target.read());
  }
  // ms[3]: the per-voxel frame drawn again from the same view, the viewer's still frame, which
  // reads the codes the frame before filled (no fill pass).
  std::vector<std::vector<double>> ms(variants.size() + 1);
  for (uint32_t f = 0; f < 2 * uint32_t(perTurn); ++f) {
    const Camera camera = gl::protocolCamera(start, f, uint32_t(perTurn));
    for (size_t v = 0; v <= variants.size(); ++v) {
      // The per-voxel frame includes its fill, even where this view is the last one's.
      if (v == 2) (*renderer)->forgetShadowCache();
      const uint64_t fills = (*renderer)->shadowFills();
      const double t0 = seconds();
      if (Status st = (*renderer)->render(camera, variants[std::min<size_t>(v, 2)], target); !st)
        return fail(st.message());
      glFinish();
      ms[v].push_back(1e3 * (seconds() - t0));
      if ((*renderer)->shadowFills() - fills != (v == 2 ? 1u : 0u))
        return fail("the shadow cache was filled where it should not, or not where it should");
    }
  }

  // The marking frame is a program compiled apart from the frame's (docs/shadows.md): on this
  // renderer, is the frame after a fill of the marked centres the frame after the full fill, byte
  // for byte, in every view? A centre the frame reads but the marking frame missed would read
  // code 0, a bright pixel. Printed on stderr, beside the table.
  uint32_t sameViews = 0, views = 0;
  size_t mostPixels = 0;
  for (uint32_t f = 0; f < 2 * uint32_t(perTurn); ++f, ++views) {
    const Camera camera = gl::protocolCamera(start, f, uint32_t(perTurn));
    Image images[2];
    for (int marked = 0; marked < 2; ++marked) {
      (*renderer)->setShadowMarking(marked ? gl::VoxLinkRenderer::ShadowMarking::kOn
                                           : gl::VoxLinkRenderer::ShadowMarking::kOff);
      (*renderer)->forgetShadowCache();
      if (Status st = (*renderer)->render(camera, perVoxel, target); !st) return fail(st.message());
      images[marked] = target.read();
    }
    size_t pixels = 0;
    for (size_t i = 0; i < images[0].rgba.size(); i += 4)
      pixels += std::memcmp(&images[0].rgba[i], &images[1].rgba[i], 4 * sizeof(float)) != 0;
    sameViews += pixels == 0;
    mostPixels = std::max(mostPixels, pixels);
  }
  (*renderer)->setShadowMarking(gl::VoxLinkRenderer::ShadowMarking::kAuto);
  std::fprintf(stderr,
               "marks (%s, %s, %ux%u): %u of %u views the same image with and without the "
               "marking frame%s (at most %zu pixels differ)\n",
               name.c_str(), argv[4], none.width, none.height, sameViews, views,
               sameViews == views ? "" : ": DIFFERENT", mostPixels);

  const ReferenceRenderer reference(*dense, *tf);
  const double r0 = seconds();
  const Image refSample = reference.render(start, perSample);
  const double r1 = seconds();
  const Image refVoxel = reference.render(start, perVoxel);
  const double r2 = seconds();
  auto psnr = [](const Image& a, const Image& b) {
    auto e = compareImages(a, b);
    return e ? e->psnr : -1.0;
  };
  const double none_ = median(ms[0]), sample = median(ms[1]), voxel = median(ms[2]),
               still = median(ms[3]);
  std::printf(
      "| %s | %s | %ux%u | %zu | %.1f | %.1f | %.1f | %.1f | %.1fx | %.2fx | %.2fx | %.1fx | %.2f "
      "| "
      "%.2f | %.2f | %.2f | %.2f | %.2f | %.2f | %.0f / %.0f | %.2f |\n",
      name.c_str(), argv[4], none.width, none.height, ms[0].size(), none_, sample, voxel, still,
      sample / none_, voxel / none_, still / none_, sample / voxel, psnr(first[0], refSample),
      psnr(first[1], refSample), psnr(first[1], refVoxel), psnr(first[2], refSample),
      psnr(first[2], refVoxel), psnr(refVoxel, refSample), psnr(first[2], first[1]),
      1e3 * (r1 - r0), 1e3 * (r2 - r1), double((*renderer)->gpuBytes() - plainBytes) / 1048576.0);
  return 0;
}

}  // namespace

int main(int argc, char** argv) { return run(argc, argv); }
