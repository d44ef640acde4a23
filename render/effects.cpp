// SPDX-License-Identifier: BSD-3-Clause
#include "render/effects.h"

#include <cmath>
#include <nlohmann/json.hpp>

namespace voxlink::render {

Result<Effects> parseEffects(std::string_view text, int maxBounces) {
  Effects e;
  e.maxBounces = maxBounces;
  if (!(maxBounces >= 0 && maxBounces <= kMaxBouncesLimit))
    return makeError(ErrorCode::kInvalidArgument, "--max-bounces: ", maxBounces, " is not in [0, ",
                     kMaxBouncesLimit, "]");
  std::string_view rest = text;
  while (!rest.empty()) {
    const size_t comma = rest.find(',');
    const std::string_view item = rest.substr(0, comma);
    if (item == "all") {
      e.reflect = e.refract = e.shadows = true;
    } else if (item == "none") {
    } else if (item == "reflect") {
      e.reflect = true;
    } else if (item == "refract") {
      e.refract = true;
    } else if (item == "shadows") {
      e.shadows = true;
    } else {
      return makeError(ErrorCode::kInvalidArgument, "--effects: '", std::string(item),
                       "' is not reflect, refract, shadows, all or none");
    }
    if (comma == std::string_view::npos) break;
    rest.remove_prefix(comma + 1);
  }
  return e;
}

std::string effectsName(const Effects& e) {
  std::string s;
  for (auto [on, name] : {std::pair{e.reflect, "reflect"}, std::pair{e.refract, "refract"},
                          std::pair{e.shadows, "shadows"}}) {
    if (!on) continue;
    if (!s.empty()) s.push_back(',');
    s.append(name);
  }
  return s.empty() ? "none" : s;
}

Result<std::vector<Light>> sceneLights(const std::string& metaJson) {
  std::vector<Light> lights;
  const auto meta = nlohmann::json::parse(metaJson, nullptr, /*allow_exceptions=*/false);
  if (!meta.is_object() || !meta.contains("scene") || !meta["scene"].is_object() ||
      !meta["scene"].contains("lights"))
    return lights;
  const nlohmann::json& list = meta["scene"]["lights"];
  if (!list.is_array()) return makeError(ErrorCode::kCorrupt, "META scene.lights: not an array");
  for (size_t i = 0; i < list.size(); ++i) {
    const std::string where = "META scene.lights[" + std::to_string(i) + "]";
    const nlohmann::json& l = list[i];
    auto vec3 = [&](const char* key, std::array<double, 3> fallback,
                    std::array<double, 3>& out) -> Status {
      out = fallback;
      if (!l.is_object() || !l.contains(key)) return Status::ok();
      const nlohmann::json& v = l[key];
      if (!v.is_array() || v.size() != 3)
        return makeError(ErrorCode::kCorrupt, where, ".", key, ": expected 3 numbers");
      for (int a = 0; a < 3; ++a) {
        if (!v[a].is_number() || !std::isfinite(v[a].get<double>()))
          return makeError(ErrorCode::kCorrupt, where, ".", key, ": expected 3 finite numbers");
        out[a] = v[a].get<double>();
      }
      return Status::ok();
    };
    Light light;
    std::array<double, 3> color;
    VOXLINK_RETURN_IF_ERROR(vec3("position", {0, 0, 0}, light.position));
    VOXLINK_RETURN_IF_ERROR(vec3("color", {1, 1, 1}, color));
    double intensity = 1.0;
    if (l.contains("intensity")) {
      if (!l["intensity"].is_number() || !(l["intensity"].get<double>() >= 0))
        return makeError(ErrorCode::kCorrupt, where, ".intensity: expected a number >= 0");
      intensity = l["intensity"].get<double>();
    }
    for (int a = 0; a < 3; ++a) light.radiance[a] = color[a] * intensity;
    lights.push_back(light);
  }
  if (lights.size() > kMaxLights)
    return makeError(ErrorCode::kUnsupported, "META scene.lights: ", lights.size(),
                     " lights; the ray tracer takes at most ", kMaxLights);
  return lights;
}

}  // namespace voxlink::render
