// SPDX-License-Identifier: BSD-3-Clause
#include "render/gl/render_benchmark.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iomanip>
#include <map>

namespace voxlink::render::gl {

namespace {

double seconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

}  // namespace

Camera protocolCamera(const Camera& start, uint32_t i, uint32_t n) {
  Camera c = start;
  const double step = 360.0 / n;
  if (i < n) {
    c.rotateAboutWorldAxis({0, 1, 0}, step * i);
  } else {
    c.rotateAboutWorldAxis({0, 1, 0}, 360.0);
    c.rotateAboutWorldAxis({1, 0, 0}, step * (i - n));
  }
  return c;
}

namespace {

std::string sizeName(uint32_t w, uint32_t h) { return std::to_string(w) + "x" + std::to_string(h); }

}  // namespace

Result<std::vector<BenchmarkRow>> runRenderBenchmark(const std::vector<VolumeRenderer*>& renderers,
                                                     const ReferenceRender& reference,
                                                     const Box& box, const BenchmarkOptions& o) {
  if (o.framesPerTurn == 0)
    return makeError(ErrorCode::kInvalidArgument,
                     "bench-render: --frames-per-turn must be positive");
  auto log = [&](const std::string& line) {
    if (o.log) o.log(line);
  };
  const Camera start = Camera::framing(box, o.camera);
  const uint32_t frames = 2 * o.framesPerTurn;
  std::vector<BenchmarkRow> rows;
  for (const auto& size : o.sizes) {
    for (Sampling sampling : o.samplings) {
      RenderSettings s = o.base;
      s.width = size[0];
      s.height = size[1];
      s.sampling = sampling;
      const std::string label =
          sizeName(s.width, s.height) + " " + std::string(samplingName(sampling));
      std::vector<RenderTarget> targets(renderers.size());
      std::vector<std::vector<double>> times(renderers.size());
      // Warm-up: compiles the program and lets llvmpipe JIT it; not timed.
      for (size_t r = 0; r < renderers.size(); ++r) {
        VOXLINK_RETURN_IF_ERROR(renderers[r]->render(start, s, targets[r]));
        glFinish();
      }
      std::vector<Image> firstFrames(renderers.size());
      for (uint32_t f = 0; f < frames; ++f) {
        const Camera camera = protocolCamera(start, f, o.framesPerTurn);
        for (size_t r = 0; r < renderers.size(); ++r) {
          // A frame with per-voxel shadow rays is timed with its fill, even where two views of
          // the protocol coincide (one frame per turn).
          renderers[r]->forgetShadowCache();
          const double t0 = seconds();
          VOXLINK_RETURN_IF_ERROR(renderers[r]->render(camera, s, targets[r]));
          glFinish();
          times[r].push_back(seconds() - t0);
          if (f == 0) firstFrames[r] = targets[r].read();
        }
        if ((f + 1) % std::max(1u, frames / 8) == 0)
          log(cat(label, ": frame ", f + 1, "/", frames));
      }
      Image truth;
      if (reference) {
        log(cat(label, ": float64 reference"));
        truth = reference(start, s);
      }
      for (size_t r = 0; r < renderers.size(); ++r) {
        BenchmarkRow row{
            renderers[r]->name(),    sampling, s.width, s.height, frames, 0, 0, 0, 0, NAN, NAN,
            renderers[r]->gpuBytes()};
        double total = 0;
        for (double t : times[r]) total += t;
        row.meanMs = 1e3 * total / frames;
        row.minMs = 1e3 * *std::min_element(times[r].begin(), times[r].end());
        row.maxMs = 1e3 * *std::max_element(times[r].begin(), times[r].end());
        row.fps = frames / total;
        if (reference) {
          VOXLINK_ASSIGN_OR_RETURN(ImageError e, compareImages(firstFrames[r], truth));
          row.psnr = e.psnr;
          row.maxError = e.maxError;
        }
        if (!o.pictureDir.empty()) {
          const std::string base = o.pictureDir + "/" + row.renderer + "_" +
                                   std::string(samplingName(sampling)) + "_" +
                                   sizeName(s.width, s.height);
          VOXLINK_RETURN_IF_ERROR(writeImage(firstFrames[r], base + ".png"));
        }
        rows.push_back(row);
      }
      if (reference && !o.pictureDir.empty())
        VOXLINK_RETURN_IF_ERROR(writeImage(truth, o.pictureDir + "/reference_" +
                                                      std::string(samplingName(sampling)) + "_" +
                                                      sizeName(s.width, s.height) + ".png"));
    }
  }
  return rows;
}

std::string benchmarkTable(const std::vector<BenchmarkRow>& rows) {
  std::string out =
      "| renderer | sampling | size | frames | mean ms | min ms | max ms | FPS | PSNR dB | max "
      "error | GPU MiB | speed-up |\n"
      "|---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
  // Speed-up of each row against the other renderers' rows of the same size and sampling.
  std::map<std::tuple<uint32_t, uint32_t, int>, double> slowest;
  for (const auto& r : rows) {
    auto& v = slowest[{r.width, r.height, int(r.sampling)}];
    v = std::max(v, r.meanMs);
  }
  char line[512];
  for (const auto& r : rows) {
    const double ref = slowest[{r.width, r.height, int(r.sampling)}];
    std::snprintf(
        line, sizeof line,
        "| %s | %s | %ux%u | %u | %.1f | %.1f | %.1f | %.2f | %s | %s | %.2f | %.2fx |\n",
        r.renderer.c_str(), std::string(samplingName(r.sampling)).c_str(), r.width, r.height,
        r.frames, r.meanMs, r.minMs, r.maxMs, r.fps,
        std::isnan(r.psnr)
            ? "-"
            : (std::isinf(r.psnr) ? "inf" : cat(std::fixed, std::setprecision(2), r.psnr).c_str()),
        std::isnan(r.maxError) ? "-" : cat(std::fixed, std::setprecision(4), r.maxError).c_str(),
        r.gpuBytes / 1048576.0, ref / r.meanMs);
    out += line;
  }
  return out;
}

}  // namespace voxlink::render::gl
