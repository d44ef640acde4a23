// SPDX-License-Identifier: BSD-3-Clause
#include "cli/render_options.h"

#include <cstdio>
#include <nlohmann/json.hpp>
#include <sstream>

#include "tf/tf_presets.h"

namespace voxlink::cli {

void RenderOptions::add(CLI::App* cmd, bool withSize) {
  if (withSize) cmd->add_option("--size", size, "Image size WxH")->capture_default_str();
  cmd->add_option("--tf", tfPath, "Transfer function JSON (docs/transfer-function.md)");
  cmd->add_option("--tf-preset", tfPreset,
                  "Built-in transfer function stretched over the stored value range")
      ->check(CLI::IsMember(tf::tfPresetNames()));
  cmd->add_option("--camera", camera,
                  "AZ,EL[,DIST[,FOV]]: azimuth and elevation in degrees, distance "
                  "(1 frames the volume), vertical field of view (default 30,20,1,30)");
  cmd->add_option("--up", up,
                  "World axis pointing up on screen (default z, or the scene file's camera)")
      ->check(CLI::IsMember({"y", "z", "-y", "-z"}));
  cmd->add_option("--sampling", sampling, "voxel (nearest, exact chords) or trilinear")
      ->check(CLI::IsMember({"voxel", "trilinear"}))
      ->capture_default_str();
  cmd->add_option("--step", step, "Trilinear step in units of the smallest voxel spacing")
      ->capture_default_str();
  cmd->add_flag("--shadows", shadows, "Shadow rays towards the light");
  cmd->add_flag("--no-shading", noShading, "Unlit colours (no Phong shading)");
  cmd->add_option(
         "--effects", effects,
         "Ray-traced scene mode: reflect, refract, shadows (comma-separated), all or none; "
         "lit by the scene file's lights (docs/effects.md)")
      ->capture_default_str();
  cmd->add_option("--max-bounces", maxBounces,
                  "Secondary-ray generations in the ray-traced mode (0-15)")
      ->capture_default_str();
  cmd->add_option("--steps-per-pass", stepsPerPass,
                  "Ray-traced mode on the GPU: occupied bricks a ray crosses per pass before it "
                  "waits for the next (does not change the image)")
      ->check(CLI::Range(1, 1 << 20))
      ->capture_default_str();
  cmd->add_option("--background", background, "Background colour R,G,B in [0, 1] (linear)")
      ->capture_default_str();
}

Result<render::RenderSettings> RenderOptions::settings(const format::VoxLinkFile& file) const {
  render::RenderSettings s;
  VOXLINK_ASSIGN_OR_RETURN(s.effects, render::parseEffects(effects, maxBounces));
  s.effects.stepsPerPass = stepsPerPass;
  if (s.effects.any()) {
    auto lights = render::sceneLights(file.metaJson());
    if (!lights) return makeError(lights.error().code, file.path(), ": ", lights.message());
    s.lights = std::move(*lights);
  }
  VOXLINK_ASSIGN_OR_RETURN(auto wh, render::parseImageSize(size));
  s.width = wh[0];
  s.height = wh[1];
  s.sampling = *render::parseSampling(sampling);
  s.stepVoxels = step;
  s.shading.shadows = shadows;
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
  VOXLINK_RETURN_IF_ERROR(render::checkSettings(s, "render"));
  return s;
}

Result<render::CameraSpec> RenderOptions::cameraSpec(const format::VoxLinkFile& file) const {
  render::CameraSpec defaults;
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
      defaults.up = render::parseUpAxis(c["up"].get<std::string>()).value_or(render::UpAxis::kZ);
  }
  if (!up.empty()) {
    auto axis = render::parseUpAxis(up);
    if (!axis)
      return makeError(ErrorCode::kInvalidArgument, "--up: \"", up, "\" is not y, z, -y or -z");
    defaults.up = *axis;
  }
  if (camera.empty()) return defaults;
  return render::parseCameraSpec(camera, defaults);
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

void SourceOptions::add(CLI::App* cmd) {
  cmd->add_option("--source", path,
                  "Dense source volume (default: the one the file's META records)");
  cmd->add_option("--source-dims", dims, "X,Y,Z of a raw --source");
  cmd->add_option("--source-type", type, "Element type of a raw --source (u8, i16, f32, ...)");
}

Result<sources::OpenOptions> SourceOptions::openOptions() const {
  sources::OpenOptions o;
  if (!dims.empty()) {
    std::array<uint32_t, 3> d{};
    char c1 = 0, c2 = 0, extra = 0;
    if (std::sscanf(dims.c_str(), "%u%c%u%c%u%c", &d[0], &c1, &d[1], &c2, &d[2], &extra) != 5 ||
        c1 != ',' || c2 != ',')
      return makeError(ErrorCode::kInvalidArgument, "--source-dims: expected X,Y,Z, got '", dims,
                       "'");
    o.dims = d;
  }
  if (!type.empty()) {
    const auto t = parseScalarName(type);
    if (!t)
      return makeError(ErrorCode::kInvalidArgument, "--source-type: unknown type '", type, "'");
    o.type = *t;
  }
  if (o.dims && o.type) o.format = "raw";
  return o;
}

}  // namespace voxlink::cli
