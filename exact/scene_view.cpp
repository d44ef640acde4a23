#include "exact/scene_view.h"

#include <nlohmann/json.hpp>

namespace voxlink::exact {

viewer::CameraSpec sceneCameraSpec(const scene::SceneDescription& scene) {
  viewer::CameraSpec spec;
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
    spec.up = viewer::parseUpAxis(c["up"].get<std::string>()).value_or(viewer::UpAxis::kZ);
  return spec;
}

std::vector<viewer::Light> sceneLights(const scene::SceneDescription& scene) {
  std::vector<viewer::Light> lights;
  for (const scene::Light& l : scene.lights) {
    viewer::Light light;
    light.position = l.position;
    for (int a = 0; a < 3; ++a) light.radiance[a] = l.color[a] * l.intensity;
    lights.push_back(light);
  }
  return lights;
}

}  // namespace voxlink::exact
