// SPDX-License-Identifier: BSD-3-Clause
#include "render/render_options.h"

#include <nlohmann/json.hpp>
#include <sstream>

#include "render/effects.h"
#include "tf/tf_presets.h"

namespace voxlink::render {

Result<RenderSettings> RenderOptions::settings(const format::VoxLinkFile& file) const {
  RenderSettings s;
  VOXLINK_ASSIGN_OR_RETURN(s.effects, parseEffects(effects, maxBounces));
  s.effects.stepsPerPass = stepsPerPass;
  if (s.effects.any()) {
    auto lights = sceneLights(file.metaJson());
    if (!lights) return makeError(lights.error().code, file.path(), ": ", lights.message());
    s.lights = std::move(*lights);
  }
  VOXLINK_ASSIGN_OR_RETURN(auto wh, parseImageSize(size));
  s.width = wh[0];
  s.height = wh[1];
  s.sampling = *parseSampling(sampling);
  if (file.isScene() && s.sampling != Sampling::kVoxel)
    return makeError(ErrorCode::kUnsupported, file.path(), ": --sampling ", sampling,
                     ": scenes (files with geometry) render with voxel sampling only");
  s.stepVoxels = step;
  s.terminationAlpha = terminationAlpha;
  s.shading.shadows = shadows;
  if (shadowRays.empty()) {
    s.shading.shadowRays = file.isScene() ? ShadowRays::kPerSample : ShadowRays::kPerVoxel;
  } else if (const auto rays = parseShadowRays(shadowRays)) {
    if (file.isScene() && *rays == ShadowRays::kPerVoxel)
      return makeError(ErrorCode::kUnsupported, file.path(),
                       ": --shadow-rays per-voxel: scenes (files with geometry) cast shadow rays "
                       "per sample");
    s.shading.shadowRays = *rays;
  } else {
    return makeError(ErrorCode::kInvalidArgument, "--shadow-rays: \"", shadowRays,
                     "\" is not per-sample or per-voxel");
  }
  s.shading.enabled = !noShading;
  std::stringstream in(background);
  std::string item;
  for (int i = 0; i < 3; ++i) {
    if (!std::getline(in, item, ','))
      return makeError(ErrorCode::kInvalidArgument, "--background: expected R,G,B, got '",
                       background, "'");
    try {
      s.background[i] = std::stod(item);
    } catch (const std::exception&) {
      return makeError(ErrorCode::kInvalidArgument, "--background: '", item, "' is not a number");
    }
  }
  VOXLINK_RETURN_IF_ERROR(checkSettings(s, "render"));
  return s;
}

Result<CameraSpec> RenderOptions::cameraSpec(const format::VoxLinkFile& file) const {
  CameraSpec defaults;
  // A scene's camera (META scene.camera, from its scene file) is the default view.
  const auto meta = nlohmann::json::parse(file.metaJson(), nullptr, /*allow_exceptions=*/false);
  const nlohmann::json* sceneCamera = nullptr;
  if (meta.is_object() && meta.contains("scene") && meta["scene"].is_object() &&
      meta["scene"].contains("camera"))
    sceneCamera = &meta["scene"]["camera"];
  if (sceneCamera && sceneCamera->is_object()) {
    const nlohmann::json& c = *sceneCamera;
    auto number = [&](const char* key, double& out) {
      if (c.contains(key) && c[key].is_number()) out = c[key].get<double>();
    };
    number("azimuth", defaults.azimuthDeg);
    number("elevation", defaults.elevationDeg);
    number("distance", defaults.distanceScale);
    number("fov", defaults.fovYDeg);
    if (c.contains("up") && c["up"].is_string())
      defaults.up = parseUpAxis(c["up"].get<std::string>()).value_or(UpAxis::kZ);
  }
  if (!up.empty()) {
    auto axis = parseUpAxis(up);
    if (!axis)
      return makeError(ErrorCode::kInvalidArgument, "--up: \"", up, "\" is not y, z, -y or -z");
    defaults.up = *axis;
  }
  if (camera.empty()) return defaults;
  return parseCameraSpec(camera, defaults);
}

Result<tf::TransferFunction> RenderOptions::transferFunction(
    const format::VoxLinkFile& file) const {
  if (!tfPath.empty()) return tf::loadTransferFunction(tfPath);
  if (!tfPreset.empty()) {
    const auto [lo, hi] = tf::displayRange(file.header().valueMin, file.header().valueMax);
    return tf::tfPreset(tfPreset, lo, hi);
  }
  return tf::defaultTransferFunction(file);
}

}  // namespace voxlink::render
