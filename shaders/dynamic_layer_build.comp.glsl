// SPDX-License-Identifier: BSD-3-Clause
// Resets the dynamic layer (render/gl/gl_dynamic_layer.h) before the raster stage rewrites it
// (gl_voxelize.frag.glsl with dynamic_layer.glsl), on the GPU, nothing read back: only the pool
// slots the last update used are zeroed and freed. Passes (uPass):
//   0  one invocation: pass 1's dispatch size from the last update's used-slot count
//   1  per row of VXL_N voxels of a used slot: zero it; the row 0 invocation frees the slot's key
// VXL_DYN_POOLS: the pool's storage buffers, slot s in buffer s / VXL_DYN_POOL_SLOTS
// (shaders/dynamic_layer.glsl).
#version 450
layout(local_size_x = 64) in;

uniform int uPass;
uniform uint uBrickCapacity;

layout(std430, binding = 6) writeonly buffer Pool { ivec4 pool[]; };
#if VXL_DYN_POOLS > 1
layout(std430, binding = 14) writeonly buffer Pool1 { ivec4 pool1[]; };
#endif
#if VXL_DYN_POOLS > 2
layout(std430, binding = 15) writeonly buffer Pool2 { ivec4 pool2[]; };
#endif
#if VXL_DYN_POOLS > 3
layout(std430, binding = 16) writeonly buffer Pool3 { ivec4 pool3[]; };
#endif
layout(std430, binding = 7) readonly buffer Counters {
  uint usedSlotCount;
  uint bricksDropped;
};
layout(std430, binding = 11) writeonly buffer SlotKeys { uint slotKeys[]; };
layout(std430, binding = 12) readonly buffer UsedSlots { uint usedSlots[]; };
layout(std430, binding = 10) writeonly buffer DispatchSize { uint dispatchSize[3]; };

const uint kRows = uint(VXL_N * VXL_N);

#define VXL_DYN_ZERO_ROW(P) \
  for (uint x = 0u; x < uint(VXL_N); ++x) P[base + x] = ivec4(0);

void main() {
  // Groups past 32768 wrap into y (the least maximum per axis is 65535).
  uint i =
      (gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x) * 64u + gl_LocalInvocationIndex;
  uint rows = min(usedSlotCount, uBrickCapacity) * kRows;
  if (uPass == 0) {
    if (i != 0u) return;
    uint groups = (rows + 63u) / 64u;
    dispatchSize[0] = min(groups, 32768u);
    dispatchSize[1] = (groups + 32767u) / 32768u;
    dispatchSize[2] = 1u;
    return;
  }
  if (i >= rows) return;
  uint slot = usedSlots[i / kRows], row = i % kRows;
  if (row == 0u) slotKeys[slot] = 0u;
#if VXL_DYN_POOLS > 1
  uint part = slot / uint(VXL_DYN_POOL_SLOTS);
  slot -= part * uint(VXL_DYN_POOL_SLOTS);
#endif
  uint base = (slot * kRows + row) * uint(VXL_N);
#if VXL_DYN_POOLS > 3
  if (part == 3u) VXL_DYN_ZERO_ROW(pool3) else
#endif
#if VXL_DYN_POOLS > 2
  if (part == 2u) VXL_DYN_ZERO_ROW(pool2) else
#endif
#if VXL_DYN_POOLS > 1
  if (part == 1u) VXL_DYN_ZERO_ROW(pool1) else
#endif
  VXL_DYN_ZERO_ROW(pool)
}
