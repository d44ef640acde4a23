// SPDX-License-Identifier: BSD-3-Clause
// voxlink bench-render FILE.vxl: the paper's protocol (360 deg about y, then 360 deg about x,
// mean FPS) for the VoxLink ray tracer and the dense 3D-texture ray caster, with the PSNR of
// each against the float64 reference, as a Markdown table.
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <sstream>

#include "cli/bench_animate.h"
#include "cli/command.h"
#include "cli/output_options.h"
#include "cli/render_options.h"
#include "format/validator.h"
#include "pack/open_file.h"
#include "render/gl/dense_renderer.h"
#include "render/gl/gl_context.h"
#include "render/gl/render_benchmark.h"
#include "render/gl/voxlink_renderer.h"
#include "render/recorded_source.h"
#include "render/reference_renderer.h"
#include "render/scene_reference_renderer.h"

namespace voxlink::cli {

CommandRunner addBenchRenderCommand(CLI::App& app) {
  struct Args {
    std::string path;
    std::vector<std::string> sizes{"512x512", "1000x1000"};
    std::vector<std::string> samplings{"voxel", "trilinear"};
    uint32_t framesPerTurn = 36;
    bool noDense = false, noReference = false;
    std::string pictures;
    bool animate = false;
    std::vector<uint32_t> resolutions, bricks;
    uint32_t frames = 60;
    SourceOptions source;
    RenderOptions render;
    OutputOptions out;
  };
  auto args = std::make_shared<Args>();
  auto* cmd = app.add_subcommand("bench-render",
                                 "Rendering benchmark: VoxLink vs dense ray caster, with PSNR");
  cmd->add_option("file", args->path, "VoxLink file (.vxl); with --animate a scene file (.json)")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("--sizes", args->sizes, "Image sizes WxH")->capture_default_str();
  cmd->add_option("--samplings", args->samplings, "Sampling modes")
      ->check(CLI::IsMember({"voxel", "trilinear"}))
      ->capture_default_str();
  cmd->add_option("--frames-per-turn", args->framesPerTurn,
                  "Frames per 360 degree turn (two turns)")
      ->capture_default_str();
  cmd->add_flag("--no-dense", args->noDense, "Skip the dense 3D-texture ray caster");
  cmd->add_flag("--no-reference", args->noReference, "Skip the float64 reference (no PSNR)");
  cmd->add_option("--pictures", args->pictures,
                  "Directory for PNGs of each run's first frame and the reference");
  cmd->add_flag("--animate", args->animate,
                "FILE is a scene file with animated meshes: time voxelize + render per frame in "
                "this process (docs/dynamic-scenes.md)");
  cmd->add_option("--resolutions", args->resolutions, "With --animate: grid resolutions")
      ->check(CLI::Range(2u, 65536u));
  cmd->add_option("--bricks", args->bricks, "With --animate: brick sizes")
      ->check(CLI::IsMember({4u, 8u, 16u, 32u}));
  cmd->add_option("--frames", args->frames, "With --animate: timed frames over one period")
      ->check(CLI::Range(1u, 100000u))
      ->capture_default_str();
  args->source.add(cmd);
  args->render.add(cmd, false);
  args->out.add(cmd, false);
  return [args] {
    if (args->animate) {
      AnimateBenchOptions a;
      a.scenePath = args->path;
      for (const auto& s : args->sizes) {
        auto wh = render::parseImageSize(s);
        if (!wh) return reportError(wh.error());
        a.sizes.push_back(*wh);
      }
      a.resolutions = args->resolutions;
      a.bricks = args->bricks;
      a.frames = args->frames;
      a.pictures = args->pictures;
      return runAnimateBenchmark(a, args->render, args->out);
    }
    if (!args->resolutions.empty() || !args->bricks.empty())
      return reportError(makeError(ErrorCode::kInvalidArgument,
                                   "bench-render: --resolutions and --bricks need --animate"));
    auto file = pack::openValidatedFile(args->path);
    if (!file) return reportError(file.error());
    render::gl::BenchmarkOptions o;
    o.framesPerTurn = args->framesPerTurn;
    o.sizes.clear();
    for (const auto& s : args->sizes) {
      auto wh = render::parseImageSize(s);
      if (!wh) return reportError(wh.error());
      o.sizes.push_back(*wh);
    }
    o.samplings.clear();
    for (const auto& s : args->samplings) o.samplings.push_back(*render::parseSampling(s));
    // Scenes render with voxel sampling only (the ray tracer refuses trilinear for them).
    if (file->isScene()) o.samplings = {render::Sampling::kVoxel};
    auto settings = args->render.settings(*file);
    if (!settings) return reportError(settings.error());
    o.base = *settings;
    auto spec = args->render.cameraSpec(*file);
    if (!spec) return reportError(spec.error());
    o.camera = *spec;
    o.pictureDir = args->pictures;
    if (!o.pictureDir.empty()) std::filesystem::create_directories(o.pictureDir);
    // Each run's line on stderr is this command's progress: shown unless -q.
    if (!args->out.quiet)
      o.log = [](const std::string& line) { std::fprintf(stderr, "%s\n", line.c_str()); };
    auto tf = args->render.transferFunction(*file);
    if (!tf) return reportError(tf.error());

    // A scene has no dense source: its reference is the float64 tracer over the same voxel
    // scene, and there is no dense peer.
    if (file->isScene()) args->noDense = true;
    std::optional<render::DenseVolume> dense;
    if (!file->isScene() && (!args->noDense || !args->noReference)) {
      auto sourceOptions = args->source.openOptions();
      if (!sourceOptions) return reportError(sourceOptions.error());
      auto loaded = render::loadSourceVolume(*file, args->source.path, *sourceOptions);
      if (!loaded) return reportError(loaded.error());
      dense = std::move(*loaded);
    }
    auto context = render::gl::createHeadlessContext();
    if (!context) return reportError(context.error());
    auto voxlink = render::gl::VoxLinkRenderer::create(*file);
    if (!voxlink) return reportError(voxlink.error());
    (*voxlink)->setTransferFunction(*tf);
    std::vector<render::gl::VolumeRenderer*> renderers{voxlink->get()};
    std::unique_ptr<render::gl::DenseRenderer> denseRenderer;
    if (!args->noDense) {
      auto d = render::gl::DenseRenderer::create(*dense, (*voxlink)->geometry());
      if (!d) return reportError(d.error());
      denseRenderer = std::move(*d);
      denseRenderer->setTransferFunction(*tf);
      renderers.push_back(denseRenderer.get());
    }
    std::optional<render::ReferenceRenderer> volumeReference;
    std::optional<render::SceneReferenceRenderer> sceneReference;
    render::gl::ReferenceRender reference;
    if (!args->noReference && file->isScene()) {
      sceneReference.emplace(*file, *tf);
      reference = [&](const render::Camera& c, const render::RenderSettings& s) {
        return sceneReference->render(c, s);
      };
    } else if (!args->noReference) {
      volumeReference.emplace(*dense, *tf);
      reference = [&](const render::Camera& c, const render::RenderSettings& s) {
        return volumeReference->render(c, s);
      };
    }

    const auto& h = file->header();
    args->out.print(
        "file: %s (%ux%ux%u, brick %u, %llu voxels = %.2f %% of %llu, %llu of %llu bricks "
        "occupied)\n",
        args->path.c_str(), h.dims[0], h.dims[1], h.dims[2], h.brickSize,
        (unsigned long long)h.voxelCount,
        100.0 * double(h.voxelCount) / (double(h.dims[0]) * h.dims[1] * h.dims[2]),
        (unsigned long long)(uint64_t{h.dims[0]} * h.dims[1] * h.dims[2]),
        (unsigned long long)h.occupiedBrickCount, (unsigned long long)file->gridBrickCount());
    const char* threads = std::getenv("LP_NUM_THREADS");
    args->out.print("GL: %s%s%s\n", (*context)->description().c_str(),
                    threads ? ", LP_NUM_THREADS=" : "", threads ? threads : "");
    args->out.print(
        "protocol: %u frames per 360 deg turn, about y then about x; step %.2f voxels; rays stop "
        "at opacity %.6f; shading %s; shadows %s%s%s; effects %s (max %d bounces, %zu scene "
        "lights)\n\n",
        o.framesPerTurn, o.base.stepVoxels, o.base.terminationAlpha,
        o.base.shading.enabled ? "on" : "off", o.base.shading.shadows ? "on, rays " : "off",
        // The dense caster casts per-sample rays whatever --shadow-rays says (docs/shadows.md).
        o.base.shading.shadows ? render::shadowRaysName(o.base.shading.shadowRays).data() : "",
        o.base.shading.shadows && o.base.shading.shadowRays == render::ShadowRays::kPerVoxel &&
                !args->noDense
            ? " (dense: per-sample)"
            : "",
        render::effectsName(o.base.effects).c_str(), o.base.effects.maxBounces,
        o.base.lights.size());
    auto rows =
        render::gl::runRenderBenchmark(renderers, reference, (*voxlink)->geometry().worldBox(), o);
    if (!rows) return reportError(rows.error());
    args->out.print("%s", render::gl::benchmarkTable(*rows).c_str());
    return 0;
  };
}

}  // namespace voxlink::cli
