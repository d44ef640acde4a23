// SPDX-License-Identifier: BSD-3-Clause
// Everything but the camera and the transfer function that decides what an image looks like.
// The GL renderers and the float64 reference renderer read the same struct, so a test can hold
// one of them to the other.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "base/error.h"
#include "render/effects.h"

namespace voxlink::render {

// How a ray turns voxels into colour (docs/viewer.md, "Rendering model").
enum class Sampling {
  // Nearest: every voxel cell the ray crosses contributes over the exact length of its chord.
  kVoxel,
  // Samples at a fixed step; each sample blends the 8 surrounding voxels' classified and shaded
  // colours with trilinear weights (opacity-weighted interpolation). Removed voxels contribute
  // nothing, so a pre-classified file renders like its dense source.
  kTrilinear,
};

std::string_view samplingName(Sampling s);  // "voxel", "trilinear"
std::optional<Sampling> parseSampling(std::string_view name);

// Where the shadow rays of Shading::shadows start (docs/shadows.md).
enum class ShadowRays {
  // One ray per composited sample, from the sample's point: exact, and the slow path.
  kPerSample,
  // One ray per voxel centre per frame, shared by every sample in that voxel (trilinear: the
  // alpha-and-weight mean over the sample's visible corners); the GL renderer caches it.
  kPerVoxel,
};

std::string_view shadowRaysName(ShadowRays r);  // "per-sample", "per-voxel"
std::optional<ShadowRays> parseShadowRays(std::string_view name);

struct Shading {
  bool enabled = true;
  double ambient = 0.3;
  double diffuse = 0.7;
  double specular = 0.25;
  double shininess = 24.0;
  // Direction towards the light in camera space (+x right, +y up, +z towards the viewer).
  std::array<double, 3> lightDirection{0.35, 0.5, 1.0};
  bool shadows = false;  // shadow rays towards the light, started as shadowRays says
  ShadowRays shadowRays = ShadowRays::kPerSample;
};

struct RenderSettings {
  uint32_t width = 512;
  uint32_t height = 512;
  Sampling sampling = Sampling::kVoxel;
  // Trilinear step in units of the smallest voxel spacing.
  double stepVoxels = 0.5;
  // Rays stop once their accumulated opacity exceeds this.
  double terminationAlpha = 0.99;
  // Shadow rays stop once their transmittance falls below this.
  double shadowTerminationTransmittance = 0.01;
  std::array<double, 3> background{0.0, 0.0, 0.0};
  Shading shading;
  // The ray-traced scene mode (docs/effects.md): reflection, refraction and shadow rays.
  Effects effects;
  // Lights of that mode; empty: the frame's directional light (shading.lightDirection).
  std::vector<Light> lights;
};

// Opacity 1 is held just below 1 so the per-unit extinction -ln(1 - alpha) stays finite; both
// renderers use this bound.
inline constexpr double kMaxUnitAlpha = 0.999999;

// Checks sizes and ranges; `where` prefixes messages (a command name).
Status checkSettings(const RenderSettings& s, const std::string& where);

// "WxH" -> width, height.
Result<std::array<uint32_t, 2>> parseImageSize(const std::string& text);

}  // namespace voxlink::render
