#version 450
// SPDX-License-Identifier: BSD-3-Clause
// Test shader (tests/viewer/glsl_layout_test.cpp): decodes every 16-bit gradient code so the
// test can compare the GLSL decoder with format::decodeGradient bit for bit.
layout(local_size_x = 64) in;

#include "gradient_codec.glsl"

layout(std430, binding = VXL_RESULTS_BINDING) writeonly restrict buffer Decoded { vec4 decoded[]; };

void main() {
  uint code = gl_GlobalInvocationID.x;
  if (code > 0xFFFFu) return;
  decoded[code] = vec4(decodeGradient(code), 0.0);
}
