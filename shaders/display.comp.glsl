#version 450
// SPDX-License-Identifier: BSD-3-Clause
// Turns a rendered image (linear RGBA32F, row 0 at the top) into what the window shows: sRGB
// encoded (as PNG screenshots are) and flipped for GL's bottom-up framebuffer.
layout(local_size_x = 8, local_size_y = 8) in;

layout(rgba32f, binding = 0) uniform readonly image2D uSource;
layout(rgba8, binding = 1) uniform writeonly image2D uDisplay;

float srgbEncode(float x) {
  x = clamp(x, 0.0, 1.0);
  return x <= 0.0031308 ? 12.92 * x : 1.055 * pow(x, 1.0 / 2.4) - 0.055;
}

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  ivec2 size = imageSize(uSource);
  if (any(greaterThanEqual(p, size))) return;
  vec4 c = imageLoad(uSource, p);
  imageStore(uDisplay, ivec2(p.x, size.y - 1 - p.y),
             vec4(srgbEncode(c.r), srgbEncode(c.g), srgbEncode(c.b), 1.0));
}
