// SPDX-License-Identifier: BSD-3-Clause
// The shadow cache of `--shadow-rays per-voxel` (docs/shadows.md): a sample's shadow
// is the transmittance from its voxel's centre (voxel sampling), or the alpha-and-weight mean of
// its visible corners' centre transmittances (trilinear). Before a frame whose world light or TF
// differs from the last fill's, the host clears the words (render/gl/detail/shadow_cache_buffer.h,
// volume_renderer.h) and the fill pass (shadow_fill.comp.glsl) walks every visible stored voxel's
// centre, or only those a marking frame found the frame reads (shadowTransmittance,
// voxlink_shadow.glsl), keeping 8 bits
// per stored voxel: 1 + round(254 T). Four voxels share a word, each set with imageAtomicOr. The
// frame only reads, through a buffer texture (a gather on llvmpipe, 2.5x cheaper than a
// storage-buffer read: section_buffers.h): its shader holds no shadow walk.
// Mirrors ReferenceRenderer's per-voxel shadow model (render/voxel_shadow_cache.h).

layout(binding = VXL_SHADOW_CACHE_UNIT) uniform usamplerBuffer uShadowCodes;
layout(r32ui, binding = VXL_SHADOW_CACHE_IMAGE) uniform uimageBuffer uShadowCodesOut;
#if VXL_SHADOW_MARK || VXL_SHADOW_MARKED
// One bit per slot: the centres the frame reads (render/gl/detail/shadow_cache_buffer.h). The
// marking frame (VXL_SHADOW_MARK) sets them, the fill (VXL_SHADOW_MARKED) walks only those.
layout(r32ui, binding = VXL_SHADOW_MARK_IMAGE) uniform uimageBuffer uShadowMarks;
#endif

const float kShadowLevels = 254.0;

// The code of transmittance t: 1 + round(254 t).
uint shadowCode(float t) { return 1u + uint(round(clamp(t, 0.0, 1.0) * kShadowLevels)); }

#if VXL_SHADOW_MARKED
// Whether the marking frame read slot `slot`.
bool shadowMarked(uint slot) {
  return ((imageLoad(uShadowMarks, int(slot >> 5u)).x >> (slot & 31u)) & 1u) != 0u;
}
#endif

// Sets voxel `slot`'s code; its word's three other bytes belong to other voxels.
void storeShadowCode(uint slot, uint code) {
  imageAtomicOr(uShadowCodesOut, int(slot >> 2u), code << ((slot & 3u) * 8u));
}

// The stored transmittance of visible voxel `slot` (its voxel word's index: the file's voxel
// index, or where row words have an apron, the extended index, copies included).
float centreShadow(uint slot) {
#if VXL_SHADOW_MARK
  // The marking frame: the frame's own traversal and termination (alpha only), so it reads
  // exactly the centres the frame will; it records them and its image is drawn over.
  imageAtomicOr(uShadowMarks, int(slot >> 5u), 1u << (slot & 31u));
  return 1.0;
#endif
  uint code = (texelFetch(uShadowCodes, int(slot >> 2u)).x >> ((slot & 3u) * 8u)) & 0xFFu;
  return float(code - 1u) / kShadowLevels;
}

// Trilinear sampling. Alpha times centre transmittance of the current cell's corners (numbered
// as cornerOffset in compositing.glsl), 0 for invisible ones; set by loadCornerShadows.
float gAT0, gAT1, gAT2, gAT3, gAT4, gAT5, gAT6, gAT7;

// The corner terms: corners come in a loop over a bit mask of the visible ones, the slot and
// alpha picked by selects, not arrays (llvmpipe keeps those in memory).
void loadCornerShadows(int v0, int v1, int v2, int v3, int v4, int v5, int v6,
                       int v7, float a0, float a1, float a2, float a3, float a4, float a5,
                       float a6, float a7) {
  gAT0 = gAT1 = gAT2 = gAT3 = gAT4 = gAT5 = gAT6 = gAT7 = 0.0;
  uint visible = (a0 > 0.0 ? 1u : 0u) | (a1 > 0.0 ? 2u : 0u) | (a2 > 0.0 ? 4u : 0u) |
                 (a3 > 0.0 ? 8u : 0u) | (a4 > 0.0 ? 16u : 0u) | (a5 > 0.0 ? 32u : 0u) |
                 (a6 > 0.0 ? 64u : 0u) | (a7 > 0.0 ? 128u : 0u);
  while (visible != 0u) {
    int m = findLSB(visible);
    visible &= visible - 1u;
    bool w = (m & 1) != 0, u = (m & 2) != 0, v = (m & 4) != 0;
    int slot = v ? (u ? (w ? v7 : v6) : (w ? v5 : v4)) : (u ? (w ? v3 : v2) : (w ? v1 : v0));
    float a = v ? (u ? (w ? a7 : a6) : (w ? a5 : a4)) : (u ? (w ? a3 : a2) : (w ? a1 : a0));
    float at = a * centreShadow(uint(slot));
    gAT0 = m == 0 ? at : gAT0;
    gAT1 = m == 1 ? at : gAT1;
    gAT2 = m == 2 ? at : gAT2;
    gAT3 = m == 3 ? at : gAT3;
    gAT4 = m == 4 ? at : gAT4;
    gAT5 = m == 5 ? at : gAT5;
    gAT6 = m == 6 ? at : gAT6;
    gAT7 = m == 7 ? at : gAT7;
  }
}

// A trilinear sample's shadow: the corners' centre transmittances weighted by trilinear weight
// (fractions f, as blendCorners) times alpha, over the sample's alpha `alpha` (> 0).
float cornerShadowMean(vec3 f, float alpha) {
  vec2 w = vec2(1.0 - f[VXL_W], f[VXL_W]);
  vec2 u = vec2(1.0 - f[VXL_U], f[VXL_U]);
  vec2 v = vec2(1.0 - f[VXL_V], f[VXL_V]);
  float uv0 = v.x * u.x, uv1 = v.x * u.y, uv2 = v.y * u.x, uv3 = v.y * u.y;
  float s = uv0 * (w.x * gAT0 + w.y * gAT1) + uv1 * (w.x * gAT2 + w.y * gAT3) +
            uv2 * (w.x * gAT4 + w.y * gAT5) + uv3 * (w.x * gAT6 + w.y * gAT7);
  return clamp(s / alpha, 0.0, 1.0);
}
