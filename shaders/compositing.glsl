// SPDX-License-Identifier: BSD-3-Clause
// Trilinear sampling shared by the sparse and the dense traversals: the cell's classified
// corners, their blend, and the shading and compositing of a sample. Included after the
// traversal's shadowTransmittance().

// Classified corners of one trilinear cell: colour and gradient weighted by opacity. Corner m
// sits at offset (bit 0 along the predominant axis w, bit 1 along u, bit 2 along v) from the
// cell's low corner, so corners 2j and 2j + 1 share a row. Dense volumes use the same order.
// Named shader-private variables, not arrays: llvmpipe keeps these in registers, while arrays
// (or struct parameters) went through memory and made trilinear sampling several times slower.
vec4 gA0, gA1, gA2, gA3, gA4, gA5, gA6, gA7;  // alpha * rgb, alpha
vec3 gL0, gL1, gL2, gL3, gL4, gL5, gL6, gL7;  // alpha * gradient direction
bool gCellVisible;  // some corner has opacity: samples in an invisible cell are skipped

// Offset of corner m in x, y, z.
ivec3 cornerOffset(int m) {
  ivec3 o;
  o[VXL_W] = m & 1;
  o[VXL_U] = (m >> 1) & 1;
  o[VXL_V] = (m >> 2) & 1;
  return o;
}

// Blends the corners with trilinear weights for fractions f (x, y, z): opacity-weighted colour,
// opacity and gradient. Mirrors ReferenceRenderer::traceTrilinear. The 8 weights first, then one
// multiply-add per corner and channel: 1.3 % fewer trilinear instructions than nested lerps
// (docs/rendering-trilinear-profile.md, fifth session).
vec4 blendCorners(vec3 f, out vec3 gradient) {
  vec2 w = vec2(1.0 - f[VXL_W], f[VXL_W]);
  vec2 u = vec2(1.0 - f[VXL_U], f[VXL_U]);
  vec2 v = vec2(1.0 - f[VXL_V], f[VXL_V]);
  float uv0 = v.x * u.x, uv1 = v.x * u.y, uv2 = v.y * u.x, uv3 = v.y * u.y;
  float c0 = uv0 * w.x, c1 = uv0 * w.y, c2 = uv1 * w.x, c3 = uv1 * w.y;
  float c4 = uv2 * w.x, c5 = uv2 * w.y, c6 = uv3 * w.x, c7 = uv3 * w.y;
  gradient = c0 * gL0 + c1 * gL1 + c2 * gL2 + c3 * gL3 + c4 * gL4 + c5 * gL5 + c6 * gL6 + c7 * gL7;
  return c0 * gA0 + c1 * gA1 + c2 * gA2 + c3 * gA3 + c4 * gA4 + c5 * gA5 + c6 * gA6 + c7 * gA7;
}

// Shades and composites one trilinear sample at index-space point p (q = p - 1/2).
void compositeSample(vec3 q, vec3 fraction, vec3 toEye, inout vec3 color,
                     inout float transmittance) {
  vec3 gradient;
  vec4 c = blendCorners(fraction, gradient);
  if (!(c.a > 0.0)) return;
  vec3 ambient, lit;
  shadeSample(c.rgb, c.a, gradient, toEye, ambient, lit);
  float a = stepAlpha(c.a);
  float shadow = 1.0;
#if VXL_SHADOWS
#if defined(VXL_SHADOW_CACHE) && VXL_SHADOW_CACHE
  shadow = cornerShadowMean(fraction, c.a);  // shadow_cache.glsl
#else
  shadow = shadowTransmittance(indexToWorld(q + 0.5));
#endif
#endif
  color += transmittance * (a / c.a) * (ambient + shadow * lit);
  transmittance *= 1.0 - a;
}

// Index of the first sample t_k = t0 + (k + 1/2) step at or after the ray o + t d leaves the
// trilinear cell `cell` (q = p - 1/2 in [cell, cell + 1)): empty cells are crossed in one step.
int firstSampleAfterCell(vec3 o, vec3 d, ivec3 cell, float t0) {
  float tExit = kBig;
  for (int a = 0; a < 3; ++a) {
    if (abs(d[a]) < kParallelEpsilon) continue;
    float plane = float(cell[a] + (d[a] > 0.0 ? 1 : 0)) + 0.5;
    tExit = min(tExit, (plane - o[a]) / d[a]);
  }
  return int(ceil((tExit - t0) / uStep - 0.5));
}

// First sample index at or after t for samples t_k = t0 + (k + 1/2) step, minus one against
// rounding (a sample evaluated twice is prevented by the caller's running index).
int firstSampleNear(float t, float t0) { return int(ceil((t - t0) / uStep - 0.5)) - 1; }
