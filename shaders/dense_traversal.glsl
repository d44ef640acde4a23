// SPDX-License-Identifier: BSD-3-Clause
// The dense 3D-texture ray caster the benchmark compares against: the same sampling, shading,
// transfer function and step as the VoxLink traversals, reading every voxel from 3D textures
// (stored value bits and gradient codes) and skipping no empty space (dense_walk.glsl).

#include "dense_walk.glsl"

void traceVoxels(vec3 o, vec3 d, float t, float t1, vec3 toEye, inout vec3 color,
                 inout float transmittance) {
  for (DenseWalk w = denseWalkBegin(o, d, t, t1); denseWalkGoesOn(w);) {
    ivec3 cell;
    float ta, tz;
    denseWalkEnter(w, cell, ta, tz);
    uint bits = texelFetch(uDenseValues, cell, 0).r;
    vec4 c = classify(bits);
    float a = correctedAlpha(c.a, tz - ta);
    if (a > 0.0) {
      vec3 ambient, lit;
      uint code = texelFetch(uDenseGradients, cell, 0).r;
      shadeSample(c.rgb, 1.0, decodeGradient(code), toEye, ambient, lit);
      float shadow = 1.0;
#if VXL_SHADOWS
      shadow = shadowTransmittance(indexToWorld(o + 0.5 * (ta + tz) * d));
#endif
      color += transmittance * a * (ambient + shadow * lit);
      transmittance *= 1.0 - a;
      if (transmittance <= uStopTransmittance) return;
    }
    if (!denseWalkLeave(w)) break;
  }
}

void denseCorner(ivec3 cell, int m, out vec4 colorAlpha, out vec3 gradient) {
  colorAlpha = vec4(0.0);
  gradient = vec3(0.0);
  ivec3 p = cell + cornerOffset(m);
  if (!insideGrid(p, uDims)) return;
  uint bits = texelFetch(uDenseValues, p, 0).r;
  if (!(classify(bits).a > 0.0)) return;
  classifyCorner(bits, texelFetch(uDenseGradients, p, 0).r, colorAlpha, gradient);
  gCellVisible = true;
}

void loadCorners(ivec3 cell) {
  gCellVisible = false;
  denseCorner(cell, 0, gA0, gL0);
  denseCorner(cell, 1, gA1, gL1);
  denseCorner(cell, 2, gA2, gL2);
  denseCorner(cell, 3, gA3, gL3);
  denseCorner(cell, 4, gA4, gL4);
  denseCorner(cell, 5, gA5, gL5);
  denseCorner(cell, 6, gA6, gL6);
  denseCorner(cell, 7, gA7, gL7);
}

void traceTrilinear(vec3 o, vec3 d, float t0, float t1, vec3 toEye, inout vec3 color,
                    inout float transmittance) {
  ivec3 cached = ivec3(-2147483647);
  int samples = int(min(ceil((t1 - t0) / uStep) + 1.0, 1e7));
  for (int k = 0; k < samples; ++k) {
    float ts = t0 + (float(k) + 0.5) * uStep;
    if (ts >= t1) break;
    vec3 q = o + ts * d - 0.5;
    vec3 fl = floor(q);
    ivec3 cell = ivec3(fl);
    if (cell != cached) {
      cached = cell;
      loadCorners(cell);
    }
    if (!gCellVisible) {
      k = max(k, min(firstSampleAfterCell(o, d, cell, t0), samples) - 1);
      continue;
    }
    compositeSample(q, q - fl, toEye, color, transmittance);
    if (transmittance <= uStopTransmittance) return;
  }
}
