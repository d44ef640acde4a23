// SPDX-License-Identifier: BSD-3-Clause
// Shadow rays through the dense volume: transmittance towards the light with voxel (nearest)
// sampling over every cell (dense_walk.glsl). Mirrors ReferenceRenderer::shadowTransmittance.

#include "dense_walk.glsl"

uniform usampler3D uDenseValues;     // stored value bits (R8UI, R16UI, R32UI)
uniform usampler3D uDenseGradients;  // polar16 codes (R16UI)

// One voxel of the shadow walk: its share of the light off `transmittance`; false when the walk
// is over (it left the grid or passed its end, or the light is all but gone).
bool denseShadowVoxel(inout DenseWalk w, inout float transmittance) {
  if (!denseWalkGoesOn(w)) return false;
  ivec3 cell;
  float ta, tz;
  denseWalkEnter(w, cell, ta, tz);
  uint bits = texelFetch(uDenseValues, cell, 0).r;
  transmittance *= 1.0 - correctedAlpha(classify(bits).a, tz - ta);
  return transmittance >= uShadowStop && denseWalkLeave(w);
}

float shadowTransmittance(vec3 worldPoint) {
  vec3 o = worldToIndex(worldPoint + uToLight * uUnit);
  vec3 d = directionToIndex(uToLight);
  vec2 range = intersectBox(o, d, vec3(uDims));
  float t = max(range.x, 0.0), t1 = range.y;
  float transmittance = 1.0;
  if (!(t < t1)) return transmittance;
  // Four voxels a pass: llvmpipe caps the loop passes of an invocation (65535 for 8 pixels
  // together, render/gl/detail/loop_limit_retrace.h), and a walk over every cell of the way to
  // the light for each sample of a ray ran past it even for one pixel alone (foot CT 256^3).
  for (DenseWalk w = denseWalkBegin(o, d, t, t1);;) {
    if (!denseShadowVoxel(w, transmittance) || !denseShadowVoxel(w, transmittance) ||
        !denseShadowVoxel(w, transmittance) || !denseShadowVoxel(w, transmittance))
      break;
  }
  return transmittance;
}
