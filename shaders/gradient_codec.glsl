// SPDX-License-Identifier: BSD-3-Clause
// Decodes 16-bit polar gradient codes (format/gradient_codec.h): code = t << 8 | p,
// theta = t pi / 254, phi = p pi / 128, t = 255 reserved (zero gradient).
// The sin/cos tables come from format::decodeGradient on the CPU, so decoding is bit-identical.

// [0, 255): (sin theta, cos theta); [255, 511): (cos phi, sin phi). A storage buffer, not a
// buffer texture: llvmpipe serves plain loads far faster than texel fetches.
layout(std430, binding = VXL_GRADIENT_TABLE_BINDING) readonly restrict buffer VxlGradientTable {
  vec2 gradientTable[];
};

vec3 decodeGradient(uint code) {
  uint t = code >> 8u;
  if (t > 254u) return vec3(0.0);
  vec2 theta = gradientTable[t];
  vec2 phi = gradientTable[255u + (code & 0xFFu)];
  return vec3(theta.x * phi.x, theta.x * phi.y, theta.y);
}
