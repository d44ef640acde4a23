// SPDX-License-Identifier: BSD-3-Clause
// voxlink render FILE.vxl -o out.png: one frame through EGL (no X server), written as PNG or
// EXR. With --reference it also renders the float64 reference (from the dense source; for a
// scene, the same voxel scene) and prints the image error.
#include <chrono>
#include <cstdio>
#include <optional>
#include <vector>

#include "base/output_file.h"
#include "cli/command.h"
#include "cli/output_options.h"
#include "cli/render_options.h"
#include "format/validator.h"
#include "pack/open_file.h"
#include "render/gl/gl_context.h"
#include "render/gl/voxlink_renderer.h"
#include "render/recorded_source.h"
#include "render/reference_renderer.h"
#include "render/scene_reference_renderer.h"
#include "sources/volume_source.h"

namespace voxlink::cli {

CommandRunner addRenderCommand(CLI::App& app) {
  struct Args {
    std::string path, output, referenceOut;
    bool reference = false;
    SourceOptions source;
    RenderOptions render;
    OutputOptions out;
  };
  auto args = std::make_shared<Args>();
  auto* cmd = app.add_subcommand("render", "Render a VoxLink file to PNG or EXR (headless, EGL)");
  cmd->add_option("file", args->path, "VoxLink file (.vxl)")->required()->check(CLI::ExistingFile);
  cmd->add_option("-o,--output", args->output,
                  "Image to write (.png: 8-bit sRGB, .exr: linear half float)")
      ->required();
  args->render.add(cmd);
  cmd->add_flag("--reference", args->reference,
                "Also render the float64 reference (from the dense source; a scene: the same voxel "
                "scene) and print PSNR and max error");
  cmd->add_option("--reference-output", args->referenceOut,
                  "Write the reference image here (implies --reference)");
  args->source.add(cmd);
  args->out.add(cmd, false);
  return [args] {
    // -o is required; --reference-output is optional (empty: not asked for).
    std::vector<std::string> outputs = {args->output};
    if (!args->referenceOut.empty()) outputs.push_back(args->referenceOut);
    for (const std::string& out : outputs)
      if (Status s = base::checkOutputTarget(out, {args->path, args->source.path}); !s)
        return reportError(s);
    auto file = pack::openValidatedFile(args->path);
    if (!file) return reportError(file.error());
    auto settings = args->render.settings(*file);
    if (!settings) return reportError(settings.error());
    auto spec = args->render.cameraSpec(*file);
    if (!spec) return reportError(spec.error());
    auto tf = args->render.transferFunction(*file);
    if (!tf) return reportError(tf.error());
    // The reference's dense source is loaded first: one that cannot fit is refused before a
    // frame is rendered or an image written.
    const bool reference = args->reference || !args->referenceOut.empty();
    std::optional<render::DenseVolume> dense;
    if (reference && !file->isScene()) {
      auto sourceOptions = args->source.openOptions();
      if (!sourceOptions) return reportError(sourceOptions.error());
      // No image may be one of the source's files (an image stack's slice, a header's data
      // file).
      auto chosen = render::chosenSource(*file, args->source.path, *sourceOptions);
      if (!chosen) return reportError(chosen.error());
      auto source = sources::openVolume(chosen->path, chosen->options);
      if (!source) return reportError(source.error());
      for (const std::string& out : outputs)
        if (Status s = base::checkOutputTarget(out, chosen->path, (*source)->info().files); !s)
          return reportError(s);
      auto loaded = render::loadSourceVolume(*file, args->source.path, *sourceOptions);
      if (!loaded) return reportError(loaded.error());
      dense = std::move(*loaded);
    }
    auto context = render::gl::createHeadlessContext();
    if (!context) return reportError(context.error());
    auto renderer = render::gl::VoxLinkRenderer::create(*file);
    if (!renderer) return reportError(renderer.error());
    (*renderer)->setTransferFunction(*tf);
    const render::Camera camera =
        render::Camera::framing((*renderer)->geometry().worldBox(), *spec);
    render::gl::RenderTarget target;
    const auto start = std::chrono::steady_clock::now();
    if (Status s = (*renderer)->render(camera, *settings, target); !s) return reportError(s);
    const render::Image image = target.read();
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (Status s = render::writeImage(image, args->output); !s) return reportError(s);
    args->out.print(
        "%s: %ux%u, %s sampling, %.3f s (first frame, includes shader compilation) on %s\n",
        args->output.c_str(), settings->width, settings->height,
        std::string(render::samplingName(settings->sampling)).c_str(), seconds,
        (*context)->description().c_str());
    if (settings->effects.any()) {
      const auto& stats = (*renderer)->lastEffectsStats();
      args->out.print("ray traced (%s): %d passes, %llu secondary rays, %llu dropped\n",
                      render::effectsName(settings->effects).c_str(), stats.passes,
                      (unsigned long long)stats.secondaryRays,
                      (unsigned long long)stats.droppedRays);
    }
    if (!reference) return 0;
    // A scene's reference traces the same voxel scene in float64 (its geometry has no dense
    // source).
    const render::Image truth =
        file->isScene() ? render::SceneReferenceRenderer(*file, *tf).render(camera, *settings)
                        : render::ReferenceRenderer(*dense, *tf).render(camera, *settings);
    if (!args->referenceOut.empty())
      if (Status s = render::writeImage(truth, args->referenceOut); !s) return reportError(s);
    auto error = render::compareImages(image, truth);
    if (!error) return reportError(error.error());
    args->out.print(
        "against the float64 reference: PSNR %.2f dB, max error %.4f, %llu pixels off by more than "
        "1/255, %llu non-finite\n",
        error->psnr, error->maxError, (unsigned long long)error->pixelsOver,
        (unsigned long long)error->nonFinite);
    return 0;
  };
}

}  // namespace voxlink::cli
