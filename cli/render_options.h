// SPDX-License-Identifier: BSD-3-Clause
// Options that `voxlink render`, `bench-render` and `view` share: image size, camera, transfer
// function, sampling and shading, turned into the viewer's structs.
#pragma once

#include <CLI/CLI.hpp>
#include <memory>
#include <string>

#include "format/voxlink_file.h"
#include "render/camera.h"
#include "render/render_settings.h"
#include "sources/volume_source.h"
#include "tf/transfer_function.h"

namespace voxlink::cli {

struct RenderOptions {
  std::string size = "512x512";
  std::string tfPath;
  std::string tfPreset;
  std::string camera;
  std::string up;  // empty: the scene's camera, else z
  std::string sampling = "voxel";
  double step = 0.5;
  bool shadows = false;
  bool noShading = false;
  std::string effects = "none";
  int maxBounces = 4;
  int stepsPerPass = 256;
  std::string background = "0,0,0";

  // Registers the options on `cmd`; `withSize` is false for commands with their own size flag.
  void add(CLI::App* cmd, bool withSize = true);
  // The settings for `file`: with --effects, a scene file's lights (META scene.lights) replace the
  // frame's directional light.
  Result<render::RenderSettings> settings(const format::VoxLinkFile& file) const;
  // --camera and --up over the file's own view (a scene's camera), over the defaults.
  Result<render::CameraSpec> cameraSpec(const format::VoxLinkFile& file) const;
  // --tf file, else --tf-preset over the file's value range, else the file's default.
  Result<tf::TransferFunction> transferFunction(const format::VoxLinkFile& file) const;
};

// --source PATH [--source-dims X,Y,Z --source-type T]: the dense volume for the reference and the
// dense peer, when META's record is not wanted (or a raw file needs its dims and type).
struct SourceOptions {
  std::string path;
  std::string dims;
  std::string type;

  void add(CLI::App* cmd);
  Result<sources::OpenOptions> openOptions() const;
};

}  // namespace voxlink::cli
