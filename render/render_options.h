// SPDX-License-Identifier: BSD-3-Clause
// What a frame is asked for as text (image size, camera, transfer function, sampling, shading,
// effects), turned into the renderers' structs for one file. The CLI's `render`, `bench-render`
// and `view` register these as options (cli/render_options.h); the Python module fills them
// from keyword arguments.
#pragma once

#include <string>

#include "base/error.h"
#include "format/voxlink_file.h"
#include "render/camera.h"
#include "render/render_settings.h"
#include "tf/transfer_function.h"

namespace voxlink::render {

struct RenderOptions {
  std::string size = "512x512";
  std::string tfPath;
  std::string tfPreset;
  std::string camera;
  std::string up;  // empty: the scene's camera, else z
  std::string sampling = "voxel";
  double step = 0.5;
  double terminationAlpha = 0.99;  // RenderSettings::terminationAlpha
  bool shadows = false;
  // ShadowRays by name; empty: per-voxel for volume files, per-sample for scenes (docs/shadows.md).
  std::string shadowRays;
  bool noShading = false;
  std::string effects = "none";
  int maxBounces = 4;
  int stepsPerPass = 256;
  std::string background = "0,0,0";

  // The settings for `file`: with --effects, a scene file's lights (META scene.lights) replace the
  // frame's directional light.
  Result<RenderSettings> settings(const format::VoxLinkFile& file) const;
  // --camera and --up over the file's own view (a scene's camera), over the defaults.
  Result<CameraSpec> cameraSpec(const format::VoxLinkFile& file) const;
  // --tf file, else --tf-preset over the file's value range, else the file's default.
  Result<tf::TransferFunction> transferFunction(const format::VoxLinkFile& file) const;
};

}  // namespace voxlink::render
