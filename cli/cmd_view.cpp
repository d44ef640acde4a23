// SPDX-License-Identifier: BSD-3-Clause
// voxlink view FILE.vxl: the interactive viewer (GLFW window; under a headless X server use
// `xvfb-run -a voxlink view ...`).
#include <cstdio>

#include "cli/command.h"
#include "cli/output_options.h"
#include "cli/render_options.h"
#include "format/validator.h"
#include "pack/open_file.h"
#include "viewer/app/viewer_app.h"

namespace voxlink::cli {

CommandRunner addViewCommand(CLI::App& app) {
  struct Args {
    std::string path;
    std::string window = "1100x800";
    int frames = 0;
    std::string screenshot, capture;
    RenderOptions render;
    OutputOptions out;  // -q for the shared vocabulary: the viewer prints nothing but errors
  };
  auto args = std::make_shared<Args>();
  auto* cmd = app.add_subcommand("view", "Interactive viewer with the transfer function editor");
  cmd->add_option("file", args->path, "VoxLink file (.vxl)")->required()->check(CLI::ExistingFile);
  cmd->add_option("--window", args->window, "Window size WxH")->capture_default_str();
  cmd->add_option("--frames", args->frames, "Quit after this many frames (smoke tests)");
  cmd->add_option("--screenshot-on-exit", args->screenshot,
                  "With --frames: write a screenshot before quitting");
  cmd->add_option("--capture-window-on-exit", args->capture,
                  "With --frames: write the whole window (panels included)");
  args->render.add(cmd, false);
  args->out.add(cmd, false);
  return [args] {
    auto file = pack::openValidatedFile(args->path);
    if (!file) return reportError(file.error());
    viewer::ViewerOptions o;
    o.path = args->path;
    auto size = render::parseImageSize(args->window);
    if (!size) return reportError(size.error());
    o.windowWidth = int((*size)[0]);
    o.windowHeight = int((*size)[1]);
    auto settings = args->render.settings(*file);
    if (!settings) return reportError(settings.error());
    o.settings = *settings;
    auto spec = args->render.cameraSpec(*file);
    if (!spec) return reportError(spec.error());
    o.camera = *spec;
    if (!args->render.tfPath.empty() || !args->render.tfPreset.empty()) {
      auto tf = args->render.transferFunction(*file);
      if (!tf) return reportError(tf.error());
      o.tf = *tf;
    }
    o.maxFrames = args->frames;
    o.screenshotOnExit = args->screenshot;
    o.windowCaptureOnExit = args->capture;
    return reportError(viewer::runViewer(o));
  };
}

}  // namespace voxlink::cli
