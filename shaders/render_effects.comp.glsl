// SPDX-License-Identifier: BSD-3-Clause
// The ray-traced scene mode (paper, section 5.2.2): one pass of rays. The primary pass
// (VXL_EFFECTS_PRIMARY 1) traces one ray per pixel from the camera and writes the pixel's
// accumulator; each later pass traces the rays the pass before spawned into the ray buffer
// (atomic counter), adds what they see to their pixels and spawns the next generation. The
// host starts passes until no ray is left or the bounce limit is reached
// (render/gl/volume_renderer_effects.cpp).
#version 450
#if VXL_EFFECTS_PRIMARY
layout(local_size_x = 8, local_size_y = 8) in;
#else
layout(local_size_x = 64) in;
#endif

#include "common.glsl"
#include "camera.glsl"
#include "dda.glsl"
#include "gradient_codec.glsl"
#include "transfer_function.glsl"
#include "shading.glsl"
#include "voxlink_access.glsl"
#include "voxlink_brick_bounds.glsl"
#include "voxlink_row_walk.glsl"
#include "voxlink_scene.glsl"
#include "voxlink_dynamic.glsl"
#include "voxlink_shadow.glsl"
#include "voxlink_scene_shading.glsl"
#include "voxlink_effects.glsl"
#include "compositing.glsl"
#include "voxlink_voxels.glsl"
#include "voxlink_dynamic_trace.glsl"

// Per pixel: r, g, b and the share that reached the background, in fixed point (kAccumScale
// per unit) so that rays of one pixel add up in any order to the same sum.
layout(std430, binding = VXL_ACCUM_BINDING) buffer Accum { uint accum[]; };
const float kAccumScale = 1048576.0;  // 2^20; render/gl/detail/effects_buffers.h
const float kAccumMax = 4000.0;       // per add, so that no sum of a pixel wraps

uint fixedPoint(float v) { return uint(clamp(v, 0.0, kAccumMax) * kAccumScale + 0.5); }

#if !VXL_EFFECTS_PRIMARY
layout(std430, binding = VXL_RAYS_IN_BINDING) readonly buffer RaysIn { GpuRay raysIn[]; };
uniform uint uRayCount;
#endif

// Traces the current ray (gRay*) from a world origin along a unit world direction.
void traceEffectsRay(vec3 originWorld, vec3 direction, out vec3 color, out float transmittance) {
  vec3 o = worldToIndex(originWorld);
  vec3 d = directionToIndex(direction);
  vec2 range = intersectBox(o, d, vec3(uDims));
  float t0 = max(range.x, 0.0), t1 = range.y;
  color = vec3(0.0);
  transmittance = 1.0;
  if (!(t0 < t1)) return;
#ifdef VXL_DYNAMIC_LAYER
  // As render_main.glsl: the static file up to the moving meshes' first voxel, then its surface
  // (which spawns this ray's reflected and refracted rays). A ray that stopped for this pass
  // (transmittance 0, continued in the next) tests the layer again from where it goes on.
  traceVoxelsAndLayer(o, d, t0, t1, -direction, color, transmittance);
#else
  traceVoxels(o, d, t0, t1, -direction, color, transmittance);
#endif
}

void main() {
#if VXL_EFFECTS_PRIMARY
  // 4x2 pixel tiles per SIMD vector, as render_main.glsl.
  uint i = gl_LocalInvocationIndex;
  uvec2 local = uvec2((i & 3u) | (((i >> 3u) & 1u) << 2u), ((i >> 2u) & 1u) | ((i >> 4u) << 1u));
  uvec2 pixel = gl_WorkGroupID.xy * 8u + local;
  if (any(greaterThanEqual(pixel, uImageSize))) return;
  gRayPixel = pixel.y * uImageSize.x + pixel.x;
  gRayWeight = 1.0;
  gRayDepth = 0;
  gRayMedium = kMediumUnknown;
  vec3 color;
  float transmittance;
  traceEffectsRay(uEyeWorld, primaryDirection(pixel), color, transmittance);
  uint base = gRayPixel * 4u;
  accum[base] = fixedPoint(color.r);
  accum[base + 1u] = fixedPoint(color.g);
  accum[base + 2u] = fixedPoint(color.b);
  accum[base + 3u] = fixedPoint(transmittance);
#else
  uint r = gl_GlobalInvocationID.x;
  if (r >= uRayCount) return;
  GpuRay ray = raysIn[r];
  gRayPixel = ray.pixelDepth & 0x03FFFFFFu;
  gRayMedium = (ray.pixelDepth >> 26u) & 3u;
  gRayDepth = int(ray.pixelDepth >> 28u);
  gRayWeight = ray.originWeight.w;
  vec3 color;
  float transmittance;
  traceEffectsRay(ray.originWeight.xyz, ray.direction, color, transmittance);
  uint base = gRayPixel * 4u;
  atomicAdd(accum[base], fixedPoint(gRayWeight * color.r));
  atomicAdd(accum[base + 1u], fixedPoint(gRayWeight * color.g));
  atomicAdd(accum[base + 2u], fixedPoint(gRayWeight * color.b));
  atomicAdd(accum[base + 3u], fixedPoint(gRayWeight * transmittance));
#endif
}
