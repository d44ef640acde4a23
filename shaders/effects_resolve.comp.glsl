// SPDX-License-Identifier: BSD-3-Clause
// The ray-traced scene mode's last pass: the per-pixel fixed-point sums of all rays
// (render_effects.comp.glsl) to the RGBA32F target: colour plus the background times the share
// that reached it; alpha = 1 - that share.
#version 450
layout(local_size_x = 8, local_size_y = 8) in;

layout(std430, binding = VXL_ACCUM_BINDING) readonly buffer Accum { uint accum[]; };
layout(rgba32f, binding = 0) uniform writeonly image2D uTarget;
uniform uvec2 uImageSize;
uniform vec3 uBackground;
const float kAccumScale = 1048576.0;

void main() {
  uvec2 pixel = gl_GlobalInvocationID.xy;
  if (any(greaterThanEqual(pixel, uImageSize))) return;
  uint base = (pixel.y * uImageSize.x + pixel.x) * 4u;
  vec3 color = vec3(accum[base], accum[base + 1u], accum[base + 2u]) / kAccumScale;
  float background = float(accum[base + 3u]) / kAccumScale;
  imageStore(uTarget, ivec2(pixel), vec4(color + background * uBackground, 1.0 - background));
}
