// SPDX-License-Identifier: BSD-3-Clause
// Transfer function lookup by stored value bits (tf/tf_table.h). Indexed tables hold
// one RGBA per stored value (u8, u16, f16 files); f32 files evaluate the TF's breakpoints.
// A 16-bit file's table holds only the values from VXL_TF_FIRST up that the file stores
// (VolumeGeometry::firstValueBits): 65,536 RGBA floats were 1 MiB.
#ifndef VXL_TF_FIRST
#define VXL_TF_FIRST 0
#endif

layout(std430, binding = VXL_TF_BINDING) readonly restrict buffer VxlTransferFunction {
  vec4 tfTable[];
};
#if !VXL_TF_BREAKPOINTS
// The same table as a buffer texture: a texel fetch is cheaper than a storage read on llvmpipe.
layout(binding = VXL_TF_UNIT) uniform samplerBuffer uTfTexels;
#endif
uniform int uTfEntries;
uniform float uValueScale;   // source = stored * scale + offset
uniform float uValueOffset;

#if VXL_TF_BREAKPOINTS
vec4 tfBreakpoints(float value) {
  if (uTfEntries == 0) return vec4(0.0);
  if (value < tfTable[0].x) return tfTable[1];
  int lo = 0, hi = uTfEntries - 1;  // largest j with u_j <= value
  while (lo < hi) {
    int mid = (lo + hi + 1) / 2;
    if (tfTable[3 * mid].x <= value) lo = mid; else hi = mid - 1;
  }
  if (lo == uTfEntries - 1) return tfTable[3 * lo + 2];
  float u0 = tfTable[3 * lo].x;
  float u1 = tfTable[3 * lo + 3].x;
  return mix(tfTable[3 * lo + 2], tfTable[3 * lo + 4],
             (value - u0) / (u1 - u0));
}
#endif

// RGBA (colour, opacity per unit length) of a voxel's stored value bits.
vec4 classify(uint bits) {
#if VXL_TF_BREAKPOINTS
  float value = uintBitsToFloat(bits) * uValueScale + uValueOffset;
  if (isnan(value) || isinf(value)) return vec4(0.0);
  return tfBreakpoints(value);
#else
  return texelFetch(uTfTexels, int(bits) - VXL_TF_FIRST);
#endif
}

#ifndef VXL_TF_PREMULTIPLIED
#define VXL_TF_PREMULTIPLIED 0  // 1: 8-bit files, texels 256.. hold (rgb * a, a) (volume_renderer.cpp)
#endif

// (colour * opacity, opacity) of a voxel's stored value bits: one fetch of the premultiplied copy
// where there is one, 3 multiplies fewer per trilinear corner.
vec4 classifyPremultiplied(uint bits) {
#if VXL_TF_PREMULTIPLIED && !VXL_TF_BREAKPOINTS
  return texelFetch(uTfTexels, int(bits) + 256);
#else
  vec4 c = classify(bits);
  return vec4(c.rgb * c.a, c.a);
#endif
}

// -log2(1 - alpha) of a voxel's stored value bits, alpha its opacity per unit length (held below
// 1 as correctedAlpha holds it): a chord of length len lets exp2(-len / uUnit * this) through, so
// a shadow walk sums these and takes one exp2 at its end instead of a pow per cell. 8-bit files
// read it from texels 512.. of the table (volume_renderer.cpp), others take a log2.
float unitOpticalDepth(uint bits) {
#if VXL_TF_PREMULTIPLIED && !VXL_TF_BREAKPOINTS
  return texelFetch(uTfTexels, int(bits) + 512).x;
#else
  return -log2(1.0 - min(classify(bits).a, kMaxUnitAlpha));
#endif
}
