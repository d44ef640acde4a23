// SPDX-License-Identifier: BSD-3-Clause
// voxlink render-exact SCENE.json -o out.png: the scene's original meshes and spheres ray traced
// exactly (Embree 3) by the float64 effects tracer. With --compare FILE.vxl it also traces the
// voxelized scene with the same tracer, camera, lights and effects, and prints what
// voxelization costs: PSNR, and the silhouette/edge error (exact/edge_error.h).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <vector>

#include "base/output_file.h"
#include "base/parallel_for.h"
#include "cli/command.h"
#include "cli/output_options.h"
#include "exact/edge_error.h"
#include "exact/exact_scene_walker.h"
#include "exact/scene_view.h"
#include "format/validator.h"
#include "pack/open_file.h"
#include "render/effects_tracer.h"
#include "render/voxel_scene_walker.h"
#include "scene/scene_description.h"

namespace voxlink::cli {

namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// The median of `repeat` renders' times (the VM's speed drifts within minutes), and the last
// image.
template <class Render>
double timeRenders(int repeat, render::Image& image, const Render& render) {
  std::vector<double> seconds;
  for (int i = 0; i < repeat; ++i) {
    const auto start = Clock::now();
    image = render();
    seconds.push_back(secondsSince(start));
  }
  std::sort(seconds.begin(), seconds.end());
  const size_t n = seconds.size();
  return n % 2 ? seconds[n / 2] : 0.5 * (seconds[n / 2 - 1] + seconds[n / 2]);
}

}  // namespace

CommandRunner addRenderExactCommand(CLI::App& app) {
  struct Args {
    std::string scene, output, compare, voxelOutput, size = "512x512", camera, up;
    std::string effects = "none";
    int maxBounces = 4;
    int repeat = 1;
    bool noShading = false;
    unsigned threads = 0;
    OutputOptions out;
  };
  auto args = std::make_shared<Args>();
  auto* cmd = app.add_subcommand(
      "render-exact",
      "Ray trace a scene file's original meshes and spheres exactly (Embree 3, float64 effects "
      "tracer); with --compare, measure what voxelization costs");
  cmd->add_option("scene", args->scene, "Scene file (.json; meshes and spheres, no volume)")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("-o,--output", args->output, "Image to write (.png or .exr)")->required();
  cmd->add_option("--size", args->size, "Image size WxH")->capture_default_str();
  cmd->add_option("--camera", args->camera,
                  "AZ,EL[,DIST[,FOV]] over the scene file's camera (as voxlink render)");
  cmd->add_option("--up", args->up, "World axis pointing up on screen")
      ->check(CLI::IsMember({"y", "z", "-y", "-z"}));
  cmd->add_option("--effects", args->effects, "reflect,refract,shadows, all or none")
      ->capture_default_str();
  cmd->add_option("--max-bounces", args->maxBounces, "Secondary-ray generations")
      ->check(CLI::Range(0, render::kMaxBouncesLimit))
      ->capture_default_str();
  cmd->add_flag("--no-shading", args->noShading, "Unlit colours (no Phong shading)");
  cmd->add_option("--compare", args->compare,
                  "The scene built by `voxlink scene build` (.vxl): trace it too and print PSNR "
                  "and the silhouette/edge error against the exact image")
      ->check(CLI::ExistingFile);
  cmd->add_option("--voxel-output", args->voxelOutput, "Write the voxel scene's image here");
  cmd->add_option("--repeat", args->repeat, "Renders per tracer; the median time is printed")
      ->check(CLI::Range(1, 100))
      ->capture_default_str();
  args->out.add(cmd, false);
  addThreadsOption(cmd, args->threads);
  return [args] {
    const base::ThreadLimit limit(args->threads);  // Embree's TBB and the effects tracer
    // -o is required; --voxel-output is optional (empty: not asked for).
    std::vector<std::string> outputs = {args->output};
    if (!args->voxelOutput.empty()) outputs.push_back(args->voxelOutput);
    for (const std::string& out : outputs)
      if (Status s = base::checkOutputTarget(out, {args->scene, args->compare}); !s)
        return reportError(s);
    if (!args->voxelOutput.empty() && args->compare.empty())
      return reportError(makeError(ErrorCode::kInvalidArgument, "--voxel-output needs --compare"));
    auto description = scene::readSceneDescription(args->scene);
    if (!description) return reportError(description.error());

    render::RenderSettings settings;
    auto size = render::parseImageSize(args->size);
    if (!size) return reportError(size.error());
    settings.width = (*size)[0];
    settings.height = (*size)[1];
    settings.shading.enabled = !args->noShading;
    auto effects = render::parseEffects(args->effects, args->maxBounces);
    if (!effects) return reportError(effects.error());
    settings.effects = *effects;
    settings.lights = exact::sceneLights(*description);
    if (Status s = render::checkSettings(settings, "render-exact"); !s) return reportError(s);

    render::CameraSpec spec = exact::sceneCameraSpec(*description);
    if (!args->up.empty()) spec.up = *render::parseUpAxis(args->up);
    if (!args->camera.empty()) {
      auto parsed = render::parseCameraSpec(args->camera, spec);
      if (!parsed) return reportError(parsed.error());
      spec = *parsed;
    }

    // With --compare, the voxel file's grid decides the box rays are clipped to; the exact
    // scene is fitted at the same resolution, so both boxes must agree.
    std::optional<format::VoxLinkFile> file;
    uint32_t resolution = 0;
    if (!args->compare.empty()) {
      auto opened = pack::openValidatedFile(args->compare);
      if (!opened) return reportError(opened.error());
      if (!opened->isScene())
        return reportError(makeError(ErrorCode::kInvalidArgument, args->compare,
                                     ": not a scene (version 2) file"));
      file.emplace(std::move(*opened));
      const auto& dims = file->header().dims;
      resolution = std::max({dims[0], dims[1], dims[2]});
    }
    const auto loadStart = Clock::now();
    auto walker = exact::ExactSceneWalker::open(*description, resolution);
    if (!walker) return reportError(walker.error());
    const double loadSeconds = secondsSince(loadStart);
    const render::Box box = (*walker)->bounds();
    std::optional<render::VoxelSceneWalker> voxels;
    if (file) {
      voxels.emplace(*file);
      const render::Box v = voxels->bounds();
      const double tolerance = 1e-4 * glm::length(box.hi - box.lo);
      if (glm::length(v.lo - box.lo) > tolerance || glm::length(v.hi - box.hi) > tolerance)
        return reportError(
            makeError(ErrorCode::kInvalidArgument, args->compare,
                      ": header: the grid box differs from the one scene build fits around ",
                      args->scene, " at ", resolution, " voxels (built from another scene file?)"));
    }

    const tf::TransferFunction noVolume;  // neither walker has volume samples
    const render::Camera camera = render::Camera::framing(box, spec);
    render::Image exactImage;
    const render::EffectsTracer exactTracer(**walker, noVolume);
    const double exactSeconds =
        timeRenders(args->repeat, exactImage, [&] { return exactTracer.render(camera, settings); });
    if (Status s = render::writeImage(exactImage, args->output); !s) return reportError(s);
    args->out.print(
        "%s: %ux%u, effects %s, exact (Embree 3, %zu triangles, %zu spheres; scene loaded and "
        "built in %.3f s): %.4f s\n",
        args->output.c_str(), settings.width, settings.height,
        render::effectsName(settings.effects).c_str(), (*walker)->triangleCount(),
        (*walker)->sphereCount(), loadSeconds, exactSeconds);
    if (!file) return 0;

    render::Image voxelImage;
    const render::EffectsTracer voxelTracer(*voxels, noVolume);
    const double voxelSeconds =
        timeRenders(args->repeat, voxelImage, [&] { return voxelTracer.render(camera, settings); });
    if (!args->voxelOutput.empty())
      if (Status s = render::writeImage(voxelImage, args->voxelOutput); !s) return reportError(s);
    auto whole = render::compareImages(voxelImage, exactImage);
    if (!whole) return reportError(whole.error());
    const auto exactHits = exact::firstHits(**walker, camera, settings.width, settings.height);
    const auto voxelHits = exact::firstHits(*voxels, camera, settings.width, settings.height);
    auto edges = exact::compareEdges(voxelImage, exactImage, voxelHits, exactHits);
    if (!edges) return reportError(edges.error());
    args->out.print("voxel scene %s (%u x %u x %u): float64 tracer %.4f s\n", args->compare.c_str(),
                    file->header().dims[0], file->header().dims[1], file->header().dims[2],
                    voxelSeconds);
    args->out.print(
        "voxel vs exact: PSNR %.2f dB; first hit differs %.3f %% of pixels (coverage %.3f %%); "
        "edge mask %.3f %% of pixels: PSNR %.2f dB there, %.2f dB elsewhere\n",
        whole->psnr, 100 * edges->firstHitMismatch, 100 * edges->coverageMismatch,
        100 * edges->edgeShare, edges->edgePsnr, edges->interiorPsnr);
    return 0;
  };
}

}  // namespace voxlink::cli
