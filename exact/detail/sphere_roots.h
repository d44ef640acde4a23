// SPDX-License-Identifier: BSD-3-Clause
// Where a ray meets a sphere, in double precision: the one formula the Embree sphere callback
// and the exact walker both use, so the hit Embree picks and the event reported agree.
#pragma once

#include <array>
#include <cmath>
#include <glm/glm.hpp>
#include <optional>

namespace voxlink::exact {

// Both roots t0 <= t1 of |o + t d - c| = r for a unit direction d; empty when the ray misses.
// The stable quadratic form keeps the small root accurate for rays starting far away.
inline std::optional<std::array<double, 2>> sphereRoots(const glm::dvec3& o, const glm::dvec3& d,
                                                        const glm::dvec3& c, double r) {
  const glm::dvec3 oc = o - c;
  const double halfB = glm::dot(oc, d);
  const double cc = glm::dot(oc, oc) - r * r;
  const double disc = halfB * halfB - cc;
  if (disc < 0) return std::nullopt;
  const double q = halfB > 0 ? -(halfB + std::sqrt(disc)) : -halfB + std::sqrt(disc);
  if (q == 0) return std::array<double, 2>{0.0, 0.0};
  const double a = q, b = cc / q;
  return std::array<double, 2>{std::min(a, b), std::max(a, b)};
}

}  // namespace voxlink::exact
