// SPDX-License-Identifier: BSD-3-Clause
// `voxlink view FILE.vxl | SCENE.json`: the interactive viewer. A GLFW window, the VoxLink ray
// tracer, the transfer function editor, camera control, reduced resolution while the user drags,
// frame time and GPU memory on screen, screenshots, re-classification from the recorded source.
#pragma once

#include <memory>
#include <optional>
#include <string>

#include "render/camera.h"
#include "render/render_settings.h"
#include "tf/transfer_function.h"

namespace voxlink::viewer {

class SceneSession;

using render::CameraSpec;
using render::RenderSettings;

struct ViewerOptions {
  std::string path;
  // A scene file prepared before the window opened (scene_session.h): the viewer shows its
  // volumeFile(), with the moving meshes drawn by the session's renderer. Null for a .vxl.
  std::shared_ptr<SceneSession> scene;
  std::optional<double> sceneTime;  // start the animation there, paused (smoke tests)
  int windowWidth = 1100, windowHeight = 800;
  RenderSettings settings;  // width and height follow the window
  CameraSpec camera;
  std::optional<tf::TransferFunction> tf;
  // Smoke tests: quit after this many frames (0: run until the window closes), writing a
  // full-resolution screenshot of the last view first when a path is given.
  int maxFrames = 0;
  std::string screenshotOnExit;
  std::string windowCaptureOnExit;  // the whole window, panels included (documentation pictures)
};

Status runViewer(const ViewerOptions& options);

}  // namespace voxlink::viewer
