// SPDX-License-Identifier: BSD-3-Clause
#include "render/render_settings.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <string_view>
#include <system_error>

namespace voxlink::render {

std::string_view samplingName(Sampling s) { return s == Sampling::kVoxel ? "voxel" : "trilinear"; }

std::optional<Sampling> parseSampling(std::string_view name) {
  if (name == "voxel" || name == "nearest") return Sampling::kVoxel;
  if (name == "trilinear") return Sampling::kTrilinear;
  return std::nullopt;
}

std::string_view shadowRaysName(ShadowRays r) {
  return r == ShadowRays::kPerSample ? "per-sample" : "per-voxel";
}

std::optional<ShadowRays> parseShadowRays(std::string_view name) {
  if (name == "per-sample") return ShadowRays::kPerSample;
  if (name == "per-voxel") return ShadowRays::kPerVoxel;
  return std::nullopt;
}

Status checkSettings(const RenderSettings& s, const std::string& where) {
  constexpr uint32_t kMaxSide = 16384;
  if (s.width == 0 || s.height == 0 || s.width > kMaxSide || s.height > kMaxSide)
    return makeError(ErrorCode::kInvalidArgument, where, ": image size ", s.width, "x", s.height,
                     " must be between 1x1 and ", kMaxSide, "x", kMaxSide);
  if (!(s.stepVoxels >= 1.0 / 64 && s.stepVoxels <= 8))
    return makeError(ErrorCode::kInvalidArgument, where, ": step ", s.stepVoxels,
                     " voxels must lie in [1/64, 8]");
  if (!(s.terminationAlpha > 0 && s.terminationAlpha <= 1))
    return makeError(ErrorCode::kInvalidArgument, where, ": termination alpha ", s.terminationAlpha,
                     " must lie in (0, 1]");
  if (!(s.shadowTerminationTransmittance >= 0 && s.shadowTerminationTransmittance < 1))
    return makeError(ErrorCode::kInvalidArgument, where, ": shadow termination ",
                     s.shadowTerminationTransmittance, " must lie in [0, 1)");
  const auto& l = s.shading.lightDirection;
  if (!std::isfinite(l[0] + l[1] + l[2]) || l[0] * l[0] + l[1] * l[1] + l[2] * l[2] == 0)
    return makeError(ErrorCode::kInvalidArgument, where,
                     ": light direction must be finite and non-zero");
  for (double c : s.background)
    if (!(c >= 0 && c <= 1))
      return makeError(ErrorCode::kInvalidArgument, where,
                       ": background components must lie in [0, 1]");
  if (!(s.effects.maxBounces >= 0 && s.effects.maxBounces <= kMaxBouncesLimit))
    return makeError(ErrorCode::kInvalidArgument, where, ": max bounces ", s.effects.maxBounces,
                     " must lie in [0, ", kMaxBouncesLimit, "]");
  if (s.lights.size() > kMaxLights)
    return makeError(ErrorCode::kInvalidArgument, where, ": ", s.lights.size(), " lights; at most ",
                     kMaxLights);
  for (const Light& light : s.lights)
    for (int a = 0; a < 3; ++a)
      if (!std::isfinite(light.position[a]) || !(light.radiance[a] >= 0) ||
          !std::isfinite(light.radiance[a]))
        return makeError(ErrorCode::kInvalidArgument, where,
                         ": light positions must be finite and radiances finite and >= 0");
  return Status::ok();
}

// Digits only, each side parsed whole: sscanf's %u took "-5" as 4294967291 and wrapped
// 4294967360 to 64.
Result<std::array<uint32_t, 2>> parseImageSize(const std::string& text) {
  const size_t x = text.find_first_of("xX");
  std::array<uint32_t, 2> size{0, 0};
  bool ok = x != std::string::npos;
  for (int i = 0; i < 2 && ok; ++i) {
    const std::string_view side =
        i == 0 ? std::string_view(text).substr(0, x) : std::string_view(text).substr(x + 1);
    const auto [end, ec] = std::from_chars(side.data(), side.data() + side.size(), size[i]);
    ok = !side.empty() && ec == std::errc() && end == side.data() + side.size() &&
         side.find_first_not_of("0123456789") == std::string_view::npos && size[i] > 0;
  }
  if (!ok)
    return makeError(ErrorCode::kInvalidArgument, "--size: expected WxH such as 512x512, got '",
                     text, "'");
  return size;
}

}  // namespace voxlink::render
