// SPDX-License-Identifier: BSD-3-Clause
// The rendering model in float64: ray/box clipping, the voxel walk, opacity correction and
// Phong shading. shaders/*.glsl implement the same formulas in float; docs/viewer.md states them.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <glm/glm.hpp>
#include <utility>

#include "render/render_settings.h"

namespace voxlink::render {

// Direction components smaller than this count as zero: the ray never crosses that axis's planes.
inline constexpr double kParallelEpsilon = 1e-12;

// [t0, t1] of the ray inside the box (t0 > t1 when it misses). Zero direction components are
// handled without dividing by zero.
inline std::pair<double, double> intersectBox(const glm::dvec3& o, const glm::dvec3& d,
                                              const glm::dvec3& lo, const glm::dvec3& hi) {
  double t0 = -HUGE_VAL, t1 = HUGE_VAL;
  for (int a = 0; a < 3; ++a) {
    if (std::abs(d[a]) < kParallelEpsilon) {
      if (o[a] < lo[a] || o[a] > hi[a]) return {1.0, 0.0};
      continue;
    }
    double ta = (lo[a] - o[a]) / d[a], tb = (hi[a] - o[a]) / d[a];
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
  }
  return {t0, t1};
}

// Opacity of a chord of `length` through matter whose opacity per `unit` length is `alpha`.
inline double correctedAlpha(double alpha, double length, double unit) {
  if (alpha <= 0 || length <= 0) return 0.0;
  return 1.0 - std::pow(1.0 - std::min(alpha, kMaxUnitAlpha), length / unit);
}

// Phong terms of a sample: colour = ambient + shadow * lit.
struct ShadedTerms {
  glm::dvec3 ambient;
  glm::dvec3 lit;
};

// `c` is the colour (premultiplied by `alpha` for blended trilinear samples; voxel samples pass
// their plain colour and alpha 1); `gradient` is the opacity-weighted sum of unit gradient
// directions (a voxel's own unit direction, or zero), so |gradient| <= alpha. The surface normal
// is -gradient. Shading is weighted by m = |gradient| / alpha, the agreement of the blended
// normals: where they cancel (both sides of a thin shell, noise) or are zero, the sample fades
// to unlit colour instead of jumping there. Specular light is white, weighted by the opacity.
inline ShadedTerms shadeSample(const glm::dvec3& c, double alpha, const glm::dvec3& gradient,
                               const glm::dvec3& toLight, const glm::dvec3& toEye,
                               const Shading& s) {
  const double len = glm::length(gradient);
  if (!s.enabled || !(len > 0) || !(alpha > 0)) return {c, glm::dvec3(0.0)};
  const double m = std::min(len / alpha, 1.0);
  const glm::dvec3 n = -gradient / len;
  const double ndl = glm::dot(n, toLight);
  double diffuse = 0, specular = 0;
  if (ndl > 0) {
    diffuse = ndl;
    const glm::dvec3 r = 2.0 * ndl * n - toLight;
    specular = std::pow(std::max(glm::dot(r, toEye), 0.0), s.shininess);
  }
  return {c * (1.0 - m + m * s.ambient),
          m * (c * (s.diffuse * diffuse) + glm::dvec3(alpha * s.specular * specular))};
}

// Surface hits in a scene cast their shadow rays from this many voxels (of the smallest
// spacing) off the surface along the normal: a voxelized surface is one to two voxels thick and
// would otherwise shadow itself. kSurfaceShadowBias in shaders/voxlink_scene_shading.glsl.
inline constexpr double kSurfaceShadowBias = 2.0;
// With fragment lists (format version 2.1) a hit lies on the stored plane or triangle: rays it
// spawns, and its shadow rays along their way, start this many voxels off it. Planes of one
// curved surface cross each other near their voxels' borders, so planes need 0.3 voxel (chosen
// on the dragon, docs/geometry.md; 0.1 gains 1.5 dB there but lets the GL tracer's shadows
// differ from the float64 walker's) yet stay inside the voxel; triangles are the surface itself
// and need only a rounding margin that float (the GL tracer) still resolves. The same in the
// shaders.
inline constexpr double kListSurfaceOffset = 0.3;
inline constexpr double kTriangleSurfaceOffset = 0.01;

// Phong terms of a surface hit in a scene: unit normal `n` facing the eye, material colour `c`,
// the frame's ambient and diffuse weights and the material's own highlight (white, strength
// `specular`, exponent at least 1). colour = ambient + shadow * lit, plus the material's emission.
inline ShadedTerms shadeSurface(const glm::dvec3& c, double specular, double shininess,
                                const glm::dvec3& n, const glm::dvec3& toLight,
                                const glm::dvec3& toEye, const Shading& s) {
  if (!s.enabled) return {c, glm::dvec3(0.0)};
  const double ndl = glm::dot(n, toLight);
  double highlight = 0;
  if (ndl > 0 && specular > 0) {
    const glm::dvec3 r = 2.0 * ndl * n - toLight;
    highlight = specular * std::pow(std::max(glm::dot(r, toEye), 0.0), std::max(shininess, 1.0));
  }
  return {c * s.ambient, c * (s.diffuse * std::max(ndl, 0.0)) + glm::dvec3(highlight)};
}

// The unit direction of a gradient, or zero (what the 16-bit codec stores, without rounding).
inline glm::dvec3 gradientDirection(const glm::dvec3& g) {
  const double len = glm::length(g);
  return len > 0 ? g / len : glm::dvec3(0.0);
}

// Walks the voxel cells of [0, dims) (index space: voxel i spans [i, i+1)) that the ray
// o + t d crosses for t in [t0, t1], calling visit(cell, tEnter, tExit); visit returns false to
// stop. Cells come front to back; their chords tile [t0, t1].
template <class Visit>
void walkVoxels(const glm::dvec3& o, const glm::dvec3& d, double t0, double t1,
                const std::array<uint32_t, 3>& dims, Visit&& visit) {
  if (!(t0 < t1)) return;
  glm::ivec3 cell, step;
  glm::dvec3 tMax, tDelta;
  const glm::dvec3 p = o + t0 * d;
  for (int a = 0; a < 3; ++a) {
    cell[a] = std::clamp(int(std::floor(p[a])), 0, int(dims[a]) - 1);
    if (d[a] > kParallelEpsilon) {
      step[a] = 1;
      tMax[a] = (cell[a] + 1 - o[a]) / d[a];
      tDelta[a] = 1.0 / d[a];
    } else if (d[a] < -kParallelEpsilon) {
      step[a] = -1;
      tMax[a] = (cell[a] - o[a]) / d[a];
      tDelta[a] = -1.0 / d[a];
    } else {
      step[a] = 0;
      tMax[a] = HUGE_VAL;
      tDelta[a] = HUGE_VAL;
    }
  }
  double t = t0;
  const int maxSteps = int(dims[0] + dims[1] + dims[2]) + 3;
  for (int i = 0; i < maxSteps && t < t1; ++i) {
    const int axis = tMax.x < tMax.y ? (tMax.x < tMax.z ? 0 : 2) : (tMax.y < tMax.z ? 1 : 2);
    const double tNext = std::min(std::max(tMax[axis], t), t1);
    if (!visit(cell, t, tNext)) return;
    t = tNext;
    cell[axis] += step[axis];
    tMax[axis] += tDelta[axis];
    if (cell[axis] < 0 || cell[axis] >= int(dims[axis])) return;
  }
}

}  // namespace voxlink::render
