// SPDX-License-Identifier: BSD-3-Clause
// The float64 optics of the ray-traced scene mode (paper, section 5.2.1, "opacity transport"):
// how a hit's share of a ray divides into local shading, a reflected ray, a refracted ray and the
// part that passes straight on, and the reflection and refraction directions.
// shaders/voxlink_effects.glsl implements the same formulas in float; docs/effects.md states them.
#pragma once

#include <cmath>
#include <cstdint>
#include <glm/glm.hpp>
#include <optional>

#include "format/layout.h"
#include "render/effects.h"

namespace voxlink::render {

// Shares of the weight w of a ray arriving at a surface with opacity a, reflectivity r and
// transmission t (r + t <= 1): local shading w a (1 - r - t), reflected ray w a r, refracted ray
// w a t, straight on w (1 - a). They sum to w. An effect that is off gives its share to local
// shading, so with every effect off this is the plain compositing of the scene renderer.
struct HitShares {
  double local = 0;
  double reflect = 0;
  double refract = 0;
  double through = 0;
};

inline HitShares splitHit(const format::MaterialRecord& m, const Effects& e) {
  const double a = m.opacity;
  const double r = e.reflect ? m.reflectivity : 0.0;
  const double t = e.refract ? m.transmission : 0.0;
  return {a * (1.0 - r - t), a * r, a * t, 1.0 - a};
}

// Transmittance of a surface for shadow rays: what passes straight plus what the refracted share
// carries through (glass casts no full shadow when refraction is on).
inline double shadowTransmittanceOf(const format::MaterialRecord& m, const Effects& e) {
  const double t = e.refract ? m.transmission : 0.0;
  return 1.0 - m.opacity * (1.0 - t);
}

// Mirror direction of unit d about unit normal n (either orientation).
inline glm::dvec3 reflectDirection(const glm::dvec3& d, const glm::dvec3& n) {
  return d - 2.0 * glm::dot(d, n) * n;
}

// Where a ray is with respect to refracting objects. A ray that has not been refracted yet does
// not know (the camera may sit inside glass) and asks the surface normal; after a refraction it
// knows, which keeps voxelized surfaces whose normals are unreliable (thin parts, where both
// sides share a voxel) from being entered twice.
enum class Medium : uint8_t { kUnknown = 0, kOutside = 1, kInside = 2 };

// Whether a ray in `medium` with unit direction d enters the object at a surface with stored
// (outward) unit normal n.
inline bool entersSurface(Medium medium, const glm::dvec3& d, const glm::dvec3& n) {
  if (medium == Medium::kUnknown) return glm::dot(d, n) < 0;
  return medium == Medium::kOutside;
}

// Snell refraction of unit d at a surface with unit normal n (either orientation) of a material
// with refractive index ior: index 1 -> ior when entering, ior -> 1 when leaving. Empty on total
// internal reflection.
inline std::optional<glm::dvec3> refractDirection(const glm::dvec3& d, const glm::dvec3& n,
                                                  double ior, bool entering) {
  const glm::dvec3 nf = glm::dot(d, n) < 0 ? n : -n;  // faces the incoming ray
  const double eta = entering ? 1.0 / ior : ior;
  const double cosI = -glm::dot(d, nf);
  const double k = 1.0 - eta * eta * (1.0 - cosI * cosI);
  if (k < 0) return std::nullopt;
  return glm::normalize(eta * d + (eta * cosI - std::sqrt(k)) * nf);
}

}  // namespace voxlink::render
