// SPDX-License-Identifier: BSD-3-Clause
// Shadow rays through the dense volume: transmittance towards the light with voxel (nearest)
// sampling over every cell (dense_walk.glsl). Mirrors ReferenceRenderer::shadowTransmittance.

#include "dense_walk.glsl"

uniform usampler3D uDenseValues;     // stored value bits (R8UI, R16UI, R32UI)
uniform usampler3D uDenseGradients;  // polar16 codes (R16UI)

float shadowTransmittance(vec3 worldPoint) {
  vec3 o = worldToIndex(worldPoint + uToLight * uUnit);
  vec3 d = directionToIndex(uToLight);
  vec2 range = intersectBox(o, d, vec3(uDims));
  float t = max(range.x, 0.0), t1 = range.y;
  float transmittance = 1.0;
  if (!(t < t1)) return transmittance;
  for (DenseWalk w = denseWalkBegin(o, d, t, t1); denseWalkGoesOn(w);) {
    ivec3 cell;
    float ta, tz;
    denseWalkEnter(w, cell, ta, tz);
    uint bits = texelFetch(uDenseValues, cell, 0).r;
    transmittance *= 1.0 - correctedAlpha(classify(bits).a, tz - ta);
    if (transmittance < uShadowStop) return transmittance;
    if (!denseWalkLeave(w)) break;
  }
  return transmittance;
}

