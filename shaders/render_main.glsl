// SPDX-License-Identifier: BSD-3-Clause
// The pixel loop shared by render_voxlink.comp.glsl and render_dense.comp.glsl, included after
// the traversal that defines traceVoxels() and traceTrilinear().

layout(rgba32f, binding = 0) uniform writeonly image2D uTarget;
uniform vec3 uBackground;

#if VXL_SHADOWS
// llvmpipe ends all loops of an invocation once its SIMD vector's loops have run 65535
// iterations together, silently; shadow rays can need more. A loop of uLoopProbe (2) iterations
// after the ray that runs short shows it: the pixel is listed and traced again, one per SIMD
// vector (render/gl/detail/loop_limit_retrace.h).
layout(std430, binding = VXL_RETRACE_BINDING) restrict buffer VxlRetrace {
  uint retraceListed;  // pixels the full pass listed
  uint retraceFailed;  // listed pixels cut short again when traced alone
  uint retracePixels[];
};
uniform int uLoopProbe;
uniform uint uRetraceItems;  // 0: the full pass; else the retrace pass over this many pixels

bool loopsCutShort() {
  int n = 0;
  for (int i = 0; i < uLoopProbe; ++i) ++n;
  return n != uLoopProbe;
}
#endif

// The pixel this invocation traces; false when it has none.
bool pixelOfInvocation(out uvec2 pixel) {
  uint i = gl_LocalInvocationIndex;
#if VXL_SHADOWS
  if (uRetraceItems > 0u) {
    // One listed pixel in each run of 8 invocations (one SIMD vector on llvmpipe).
    uint item = gl_WorkGroupID.x * 8u + (i >> 3u);
    if ((i & 7u) != 0u || item >= uRetraceItems) return false;
    pixel = uvec2(retracePixels[item] & 0xFFFFu, retracePixels[item] >> 16u);
    return true;
  }
#endif
  // Each run of 8 consecutive invocations (one SIMD vector on llvmpipe) takes a 4x2 pixel tile
  // instead of a 8x1 line: closer rays take more similar paths, so fewer lanes wait (measured
  // 3-5 % on the voxel traversal).
  uvec2 local = uvec2((i & 3u) | (((i >> 3u) & 1u) << 2u), ((i >> 2u) & 1u) | ((i >> 4u) << 1u));
  pixel = gl_WorkGroupID.xy * 8u + local;
  return all(lessThan(pixel, uImageSize));
}

void main() {
  uvec2 pixel;
  if (!pixelOfInvocation(pixel)) return;
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
#if VXL_SHADOWS
  if (loopsCutShort()) {
    if (uRetraceItems > 0u) {
      atomicAdd(retraceFailed, 1u);
    } else {
      uint slot = atomicAdd(retraceListed, 1u);
      if (slot < uImageSize.x * uImageSize.y) retracePixels[slot] = pixel.x | (pixel.y << 16u);
    }
  }
#endif
  imageStore(uTarget, ivec2(pixel), vec4(color + transmittance * uBackground, 1.0 - transmittance));
}
