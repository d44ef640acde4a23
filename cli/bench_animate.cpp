// SPDX-License-Identifier: BSD-3-Clause
#include "cli/bench_animate.h"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include "cli/command.h"
#include "format/bricked_volume.h"
#include "render/camera.h"
#include "render/gl/gl_context.h"
#include "render/gl/render_target.h"
#include "render/gl/voxlink_renderer.h"
#include "render/image.h"
#include "scene/scene_assembly.h"
#include "scene/scene_description.h"
#include "viewer/dynamic_scene.h"

namespace voxlink::cli {
namespace {

using Clock = std::chrono::steady_clock;

double msSince(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// The q-quantile of `v` (nearest rank).
double quantile(std::vector<double> v, double q) {
  std::sort(v.begin(), v.end());
  const size_t rank = size_t(std::ceil(q * double(v.size())));
  return v[std::min(v.size() - 1, rank > 0 ? rank - 1 : 0)];
}

// The static part's scratch file: removed when the run ends, however it ends.
struct ScratchFile {
  std::string path;
  ~ScratchFile() {
    std::error_code ec;
    std::filesystem::remove(path, ec);
  }
};

}  // namespace

int runAnimateBenchmark(const AnimateBenchOptions& o, const render::RenderOptions& renderOptions,
                        const OutputOptions& out) {
  auto description = scene::readSceneDescription(o.scenePath);
  if (!description) return reportError(description.error());
  auto context = render::gl::createHeadlessContext();
  if (!context) return reportError(context.error());
  const std::vector<uint32_t> resolutions =
      o.resolutions.empty() ? std::vector<uint32_t>{description->grid.resolution} : o.resolutions;
  const std::vector<uint32_t> bricks =
      o.bricks.empty() ? std::vector<uint32_t>{description->grid.brickSize} : o.bricks;
  const double span = description->animationSpan();
  const char* threads = std::getenv("LP_NUM_THREADS");
  out.print("scene: %s, %u frames over %.3g s of animation\nGL: %s%s%s\n", o.scenePath.c_str(),
            o.frames, span, (*context)->description().c_str(), threads ? ", LP_NUM_THREADS=" : "",
            threads ? threads : "");
  out.print(
      "per frame: the moving meshes re-voxelized and the moving spheres re-marked on the GPU (no "
      "read-back) + a plain frame; times in ms, wall clock with glFinish after each part; "
      "static scene frame: the scene frozen at time 0, built whole (scene build) and drawn as a "
      "static file with the same camera\n\n");
  out.print(
      "| resolution | brick | size | moving triangles | layer MB | static build s | voxelize "
      "median | render median | frame median | frame p95 | FPS (1 / median) | moving spheres | "
      "static scene frame median |\n"
      "|---:|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  ScratchFile scratch{(std::filesystem::temp_directory_path() /
                       ("voxlink-animate-" + std::to_string(getpid()) + ".vxl"))
                          .string()};
  ScratchFile frozenScratch{(std::filesystem::temp_directory_path() /
                             ("voxlink-animate-frozen-" + std::to_string(getpid()) + ".vxl"))
                                .string()};
  for (uint32_t resolution : resolutions)
    for (uint32_t brick : bricks) {
      scene::SceneDescription d = *description;
      d.grid.resolution = resolution;
      d.grid.brickSize = brick;
      auto dynamic = viewer::DynamicScene::load(d, scratch.path);
      if (!dynamic) return reportError(dynamic.error());
      viewer::DynamicScene& ds = **dynamic;
      auto staticFile = format::VoxLinkFile::open(scratch.path);
      if (!staticFile) return reportError(staticFile.error());
      auto settings = renderOptions.settings(*staticFile);
      if (!settings) return reportError(settings.error());
      auto spec = renderOptions.cameraSpec(*staticFile);
      if (!spec) return reportError(spec.error());
      auto tf = renderOptions.transferFunction(*staticFile);
      if (!tf) return reportError(tf.error());
      ds.renderer().setTransferFunction(*tf);
      const render::Camera camera =
          render::Camera::framing(ds.renderer().geometry().worldBox(), *spec);
      // The same scene static: every object at its pose at time 0, built as `scene build` does.
      auto frozen = scene::buildScene(ds.frozenAt(0));
      if (!frozen) return reportError(frozen.error());
      if (Status st = format::writeBrickedVolume(frozenScratch.path, frozen->volume); !st)
        return reportError(st);
      auto frozenFile = format::VoxLinkFile::open(frozenScratch.path);
      if (!frozenFile) return reportError(frozenFile.error());
      auto frozenRenderer = render::gl::VoxLinkRenderer::create(*frozenFile);
      if (!frozenRenderer) return reportError(frozenRenderer.error());
      (*frozenRenderer)->setTransferFunction(*tf);
      for (const auto& [width, height] : o.sizes) {
        render::RenderSettings s = *settings;
        s.width = width;
        s.height = height;
        render::gl::RenderTarget target;
        // A first frame compiles the programs and sizes the buffers; not timed.
        if (Status st = ds.setTime(0); !st) return reportError(st);
        if (Status st = ds.renderer().render(camera, s, target); !st) return reportError(st);
        glFinish();
        if (!o.pictures.empty()) {
          std::filesystem::create_directories(o.pictures);
          const std::string png = o.pictures + "/animate_" + std::to_string(resolution) + "_" +
                                  std::to_string(brick) + "_" + std::to_string(width) + "x" +
                                  std::to_string(height) + ".png";
          if (Status st = render::writeImage(target.read(), png); !st) return reportError(st);
        }
        std::vector<double> voxelize, draw, frame;
        for (uint32_t i = 0; i < o.frames; ++i) {
          const double t = span * double(i) / double(o.frames);
          const auto start = Clock::now();
          if (Status st = ds.setTime(t); !st) return reportError(st);
          glFinish();
          voxelize.push_back(msSince(start));
          const auto renderStart = Clock::now();
          if (Status st = ds.renderer().render(camera, s, target); !st) return reportError(st);
          glFinish();
          draw.push_back(msSince(renderStart));
          frame.push_back(msSince(start));
          // A guard outside the timing: a layer that ran out of room is an error, not a frame.
          if (Status st = ds.checkLastUpdate(); !st) return reportError(st);
        }
        // The static scene's frame, one untimed first, then as many as the animated ones.
        if (Status st = (*frozenRenderer)->render(camera, s, target); !st) return reportError(st);
        glFinish();
        std::vector<double> staticFrame;
        for (uint32_t i = 0; i < o.frames; ++i) {
          const auto start = Clock::now();
          if (Status st = (*frozenRenderer)->render(camera, s, target); !st) return reportError(st);
          glFinish();
          staticFrame.push_back(msSince(start));
        }
        const double median = quantile(frame, 0.5);
        out.print(
            "| %u | %u | %ux%u | %llu | %.1f | %.2f | %.1f | %.1f | %.1f | %.1f | %.1f | %llu "
            "| %.1f |\n",
            resolution, brick, width, height,
            static_cast<unsigned long long>(ds.stats().movingTriangles),
            double(ds.stats().layerBytes) / (1 << 20), ds.stats().staticBuildSeconds,
            quantile(voxelize, 0.5), quantile(draw, 0.5), median, quantile(frame, 0.95),
            1000.0 / median, static_cast<unsigned long long>(ds.stats().movingSpheres),
            quantile(staticFrame, 0.5));
      }
    }
  return 0;
}

}  // namespace voxlink::cli
