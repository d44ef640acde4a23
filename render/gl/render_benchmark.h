// SPDX-License-Identifier: BSD-3-Clause
// The paper's rendering protocol (section 6): a 360 degree turn about the y axis, then one about
// the x axis, mean frame rate over both. Renderers run interleaved frame by frame, so a load
// change on a shared machine hits them alike; each gets its PSNR against the float64 reference.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "render/camera.h"
#include "render/gl/detail/volume_renderer.h"
#include "render/image.h"
#include "render/reference_renderer.h"
#include "render/render_settings.h"

namespace voxlink::render::gl {

struct BenchmarkOptions {
  uint32_t framesPerTurn = 36;
  std::vector<std::array<uint32_t, 2>> sizes{{512, 512}, {1000, 1000}};
  std::vector<Sampling> samplings{Sampling::kVoxel, Sampling::kTrilinear};
  RenderSettings base;  // everything but size and sampling
  CameraSpec camera;
  // Where to write the first frame of each run (and the reference) as PNG; empty: nowhere.
  std::string pictureDir;
  std::function<void(const std::string&)> log;  // progress lines; may be empty
};

struct BenchmarkRow {
  std::string renderer;
  Sampling sampling;
  uint32_t width, height;
  uint32_t frames;
  double meanMs;  // mean frame time over the protocol
  double minMs, maxMs;
  double fps;   // frames / total time
  double psnr;  // first view, against the reference
  double maxError;
  uint64_t gpuBytes;
};

// The float64 image a frame is compared with: a volume's ReferenceRenderer, or for a scene the
// tracer over the same voxel scene. Empty: no PSNR column.
using ReferenceRender = std::function<Image(const Camera&, const RenderSettings&)>;

// View i of the benchmark's rotation protocol (the paper's): turns 0..n-1 about y, then n..2n-1
// about x, from `start`.
Camera protocolCamera(const Camera& start, uint32_t i, uint32_t n);

// Renderers must share the TF already set on them.
Result<std::vector<BenchmarkRow>> runRenderBenchmark(const std::vector<VolumeRenderer*>& renderers,
                                                     const ReferenceRender& reference,
                                                     const Box& box,
                                                     const BenchmarkOptions& options);

// Markdown table with the speed-up of the first renderer over each other one.
std::string benchmarkTable(const std::vector<BenchmarkRow>& rows);

}  // namespace voxlink::render::gl
