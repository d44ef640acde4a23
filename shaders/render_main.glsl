// SPDX-License-Identifier: BSD-3-Clause
// The pixel loop shared by render_voxlink.comp.glsl and render_dense.comp.glsl, included after
// the traversal that defines traceVoxels() and traceTrilinear().

layout(rgba32f, binding = 0) uniform writeonly image2D uTarget;
uniform vec3 uBackground;

void main() {
  // Each run of 8 consecutive invocations (one SIMD vector on llvmpipe) takes a 4x2 pixel tile
  // instead of a 8x1 line: closer rays take more similar paths, so fewer lanes wait (measured
  // 3-5 % on the voxel traversal).
  uint i = gl_LocalInvocationIndex;
  uvec2 local = uvec2((i & 3u) | (((i >> 3u) & 1u) << 2u), ((i >> 2u) & 1u) | ((i >> 4u) << 1u));
  uvec2 pixel = gl_WorkGroupID.xy * 8u + local;
  if (any(greaterThanEqual(pixel, uImageSize))) return;
  vec3 direction = primaryDirection(pixel);
  vec3 o = worldToIndex(uEyeWorld);
  vec3 d = directionToIndex(direction);
  vec2 range = intersectBox(o, d, vec3(uDims));
  float t0 = max(range.x, 0.0), t1 = range.y;
  vec3 color = vec3(0.0);
  float transmittance = 1.0;
  if (t0 < t1) {
#if VXL_TRILINEAR
    traceTrilinear(o, d, t0, t1, -direction, color, transmittance);
#elif defined(VXL_DYNAMIC_LAYER)
    traceVoxelsAndLayer(o, d, t0, t1, -direction, color, transmittance);
#else
    traceVoxels(o, d, t0, t1, -direction, color, transmittance);
#endif
  }
  imageStore(uTarget, ivec2(pixel), vec4(color + transmittance * uBackground, 1.0 - transmittance));
}
