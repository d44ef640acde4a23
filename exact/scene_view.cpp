// SPDX-License-Identifier: BSD-3-Clause
#include "exact/scene_view.h"

#include <nlohmann/json.hpp>

namespace voxlink::exact {

render::CameraSpec sceneCameraSpec(const scene::SceneDescription& scene) {
  render::CameraSpec spec;
  if (scene.cameraJson.empty()) return spec;
  const auto c = nlohmann::json::parse(scene.cameraJson, nullptr, /*allow_exceptions=*/false);
  if (!c.is_object()) return spec;
  auto number = [&](const char* key, double& out) {
    if (c.contains(key) && c[key].is_number()) out = c[key].get<double>();
  };
  number("azimuth", spec.azimuthDeg);
  number("elevation", spec.elevationDeg);
  number("distance", spec.distanceScale);
  number("fov", spec.fovYDeg);
  if (c.contains("up") && c["up"].is_string())
    spec.up = render::parseUpAxis(c["up"].get<std::string>()).value_or(render::UpAxis::kZ);
  return spec;
}

std::vector<render::Light> sceneLights(const scene::SceneDescription& scene) {
  std::vector<render::Light> lights;
  for (const scene::Light& l : scene.lights) {
    render::Light light;
    light.position = l.position;
    for (int a = 0; a < 3; ++a) light.radiance[a] = l.color[a] * l.intensity;
    lights.push_back(light);
  }
  return lights;
}

}  // namespace voxlink::exact
