// SPDX-License-Identifier: BSD-3-Clause
// Saves and restores the bricks of a kept dynamic layer (render/gl/gl_dynamic_layer.h, keep()):
// the meshes that did not move keep their voxels by a copy instead of a re-voxelization. The
// brick map, hash keys and used-slot list are copied whole by the host; this copies the pool's
// used slots, packed in the kept buffer in used-slot order. Passes (uPass):
//   0  save:    kept[i] = pool[the i-th used slot's voxels]
//   1  restore: pool[the i-th used slot's voxels] = kept[i]
// VXL_DYN_POOLS: the pool's storage buffers, slot s in buffer s / VXL_DYN_POOL_SLOTS
// (shaders/dynamic_layer.glsl); the kept bricks are split the same way (kept brick k in kept
// buffer k / VXL_DYN_POOL_SLOTS).
#version 450
layout(local_size_x = 64) in;

uniform int uPass;
uniform uint uBricks;  // used slots kept

layout(std430, binding = 6) buffer Pool { ivec4 pool[]; };
layout(std430, binding = 12) readonly buffer UsedSlots { uint usedSlots[]; };
layout(std430, binding = 13) buffer Kept { ivec4 kept[]; };
#if VXL_DYN_POOLS > 1
layout(std430, binding = 14) buffer Pool1 { ivec4 pool1[]; };
layout(std430, binding = 17) buffer Kept1 { ivec4 kept1[]; };
#endif
#if VXL_DYN_POOLS > 2
layout(std430, binding = 15) buffer Pool2 { ivec4 pool2[]; };
layout(std430, binding = 18) buffer Kept2 { ivec4 kept2[]; };
#endif
#if VXL_DYN_POOLS > 3
layout(std430, binding = 16) buffer Pool3 { ivec4 pool3[]; };
layout(std430, binding = 19) buffer Kept3 { ivec4 kept3[]; };
#endif

const uint kVoxels = uint(VXL_N * VXL_N * VXL_N);

// A brick index split into its buffer (part) and voxel v's element there (e).
#define VXL_DYN_SPLIT(brick, part, e)              \
  uint part = brick / uint(VXL_DYN_POOL_SLOTS);    \
  uint e = (brick - part * uint(VXL_DYN_POOL_SLOTS)) * kVoxels + v;

ivec4 readBrickVoxel(bool fromPool, uint brick, uint v) {
  VXL_DYN_SPLIT(brick, part, e)
#if VXL_DYN_POOLS > 3
  if (part == 3u) return fromPool ? pool3[e] : kept3[e];
#endif
#if VXL_DYN_POOLS > 2
  if (part == 2u) return fromPool ? pool2[e] : kept2[e];
#endif
#if VXL_DYN_POOLS > 1
  if (part == 1u) return fromPool ? pool1[e] : kept1[e];
#endif
  return fromPool ? pool[e] : kept[e];
}

void writeBrickVoxel(bool toPool, uint brick, uint v, ivec4 value) {
  VXL_DYN_SPLIT(brick, part, e)
#if VXL_DYN_POOLS > 3
  if (part == 3u) {
    if (toPool) pool3[e] = value; else kept3[e] = value;
    return;
  }
#endif
#if VXL_DYN_POOLS > 2
  if (part == 2u) {
    if (toPool) pool2[e] = value; else kept2[e] = value;
    return;
  }
#endif
#if VXL_DYN_POOLS > 1
  if (part == 1u) {
    if (toPool) pool1[e] = value; else kept1[e] = value;
    return;
  }
#endif
  if (toPool) pool[e] = value; else kept[e] = value;
}

void main() {
  // Groups past 32768 wrap into y (the least maximum per axis is 65535).
  uint i =
      (gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x) * 64u + gl_LocalInvocationIndex;
  if (i >= uBricks * kVoxels) return;
  uint slot = usedSlots[i / kVoxels], k = i / kVoxels, v = i % kVoxels;
  if (uPass == 0)
    writeBrickVoxel(false, k, v, readBrickVoxel(true, slot, v));
  else
    writeBrickVoxel(true, slot, v, readBrickVoxel(false, k, v));
}
