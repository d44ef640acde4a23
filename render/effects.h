// SPDX-License-Identifier: BSD-3-Clause
// Global effects of the ray-traced scene mode (paper, section 5.2): which secondary rays are
// traced, how deep, and the lights they are traced towards. Part of RenderSettings, so the GL
// ray tracer and both float64 references read the same switches.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "base/error.h"

namespace voxlink::render {

struct Effects {
  bool reflect = false;  // mirror rays at reflective surfaces (material reflectivity)
  bool refract = false;  // Snell refraction at transmissive surfaces (transmission, ior)
  bool shadows = false;  // a shadow ray towards every light at every hit
  // Secondary-ray generations after the primary ray; a ray past it is not spawned (its share is
  // lost, as in any bounded ray tracer). At most kMaxBouncesLimit.
  int maxBounces = 4;
  // GPU only (the image does not depend on it): a ray crosses at most this many occupied bricks
  // in one pass and then waits for the next, so that the lanes of a pass do not wait for the
  // longest ray (paper, 5.2.2).
  int stepsPerPass = 256;

  bool any() const { return reflect || refract || shadows; }
};

// "reflect,refract,shadows", "all" or "none" (the --effects option).
Result<Effects> parseEffects(std::string_view text, int maxBounces);
std::string effectsName(const Effects& e);  // "reflect,shadows", "none"

// A light of the effects mode. Point lights come from a scene file (META scene.lights); without
// them the frame's directional light is used. No distance falloff: a light's radiance arrives
// undimmed, as the directional light's does (docs/effects.md).
struct Light {
  std::array<double, 3> position{0, 0, 0};  // world; for a directional light: towards the light
  std::array<double, 3> radiance{1, 1, 1};  // colour * intensity
  bool directional = false;
};

// At most this many lights reach the GL ray tracer (one uniform array); more are refused.
inline constexpr size_t kMaxLights = 8;
inline constexpr int kMaxBouncesLimit = 15;  // a 4-bit field of the GPU's ray record

// Lights from a VoxLink file's META JSON (scene.lights: position, color, intensity); empty when
// it has none. Malformed entries are an error naming the field.
Result<std::vector<Light>> sceneLights(const std::string& metaJson);

}  // namespace voxlink::render
