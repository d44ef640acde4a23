// SPDX-License-Identifier: BSD-3-Clause
// voxlink view FILE.vxl | SCENE.json: the interactive viewer (GLFW window; under a headless X
// server use `xvfb-run -a voxlink view ...`). A scene file is built in memory first, as
// `scene build` builds it, so a bad one is a one-line error before any window opens.
#include <cstdio>

#include "cli/command.h"
#include "cli/output_options.h"
#include "cli/progress_bar.h"
#include "cli/render_options.h"
#include "format/validator.h"
#include "pack/open_file.h"
#include "viewer/app/scene_session.h"
#include "viewer/app/viewer_app.h"

namespace voxlink::cli {
namespace {

bool isSceneFile(const std::string& path) {
  return path.size() > 5 && path.compare(path.size() - 5, 5, ".json") == 0;
}

}  // namespace

CommandRunner addViewCommand(CLI::App& app) {
  struct Args {
    std::string path;
    std::string window = "1100x800";
    int frames = 0;
    std::string screenshot, capture;
    uint32_t resolution = 0, brick = 0;  // scene files
    double time = -1;
    RenderOptions render;
    OutputOptions out;  // -q: no progress bar while a scene builds; otherwise only errors
  };
  auto args = std::make_shared<Args>();
  auto* cmd = app.add_subcommand("view", "Interactive viewer with the transfer function editor");
  cmd->add_option("file", args->path, "VoxLink file (.vxl) or scene file (.json, docs/scene.md)")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("--resolution", args->resolution,
                  "scene files: voxels along the scene's longest axis (overrides grid.resolution, "
                  "as for scene build)")
      ->check(CLI::Range(2u, 65536u));
  cmd->add_option("--brick", args->brick,
                  "scene files: brick edge 4, 8, 16 or 32 (overrides grid.brick)")
      ->check(CLI::IsMember({4u, 8u, 16u, 32u}));
  cmd->add_option("--time", args->time,
                  "scene files with an animation: start at this time (seconds), paused")
      ->check(finiteNumber())
      ->check(CLI::Range(0.0, 1e9));  // after finiteNumber: no comparison refuses NaN
  cmd->add_option("--window", args->window, "Window size WxH")->capture_default_str();
  cmd->add_option("--frames", args->frames, "Quit after this many frames (smoke tests)");
  cmd->add_option("--screenshot-on-exit", args->screenshot,
                  "With --frames: write a screenshot before quitting");
  cmd->add_option("--capture-window-on-exit", args->capture,
                  "With --frames: write the whole window (panels included)");
  args->render.add(cmd, false);
  args->out.add(cmd, true);
  return [args] {
    viewer::ViewerOptions o;
    o.path = args->path;
    std::string volume = args->path;
    if (isSceneFile(args->path)) {
      ProgressBar bar(args->out.showProgress());
      auto session =
          viewer::SceneSession::prepare(args->path, {args->resolution, args->brick},
                                        [&](const char* stage, double f) { bar.update(f, stage); });
      if (!session) return bar.fail(session.error());
      bar.finish();
      o.scene = std::move(*session);
      volume = o.scene->volumeFile();
      if (args->time >= 0) o.sceneTime = args->time;
    } else if (args->resolution || args->brick || args->time >= 0) {
      return reportError(makeError(ErrorCode::kInvalidArgument, args->path,
                                   ": --resolution, --brick and --time are for scene files"));
    }
    auto file = pack::openValidatedFile(volume);
    if (!file) return reportError(file.error());
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
