// SPDX-License-Identifier: BSD-3-Clause
// Saves and restores the bricks of a kept dynamic layer (render/gl/gl_dynamic_layer.h, keep()):
// the meshes that did not move keep their voxels by a copy instead of a re-voxelization. The
// brick map, hash keys and used-slot list are copied whole by the host; this copies the pool's
// used slots, packed in the kept buffer in used-slot order. Passes (uPass):
//   0  save:    kept[i] = pool[the i-th used slot's voxels]
//   1  restore: pool[the i-th used slot's voxels] = kept[i]
#version 450
layout(local_size_x = 64) in;

uniform int uPass;
uniform uint uBricks;  // used slots kept

layout(std430, binding = 6) buffer Pool { ivec4 pool[]; };
layout(std430, binding = 12) readonly buffer UsedSlots { uint usedSlots[]; };
layout(std430, binding = 13) buffer Kept { ivec4 kept[]; };

const uint kVoxels = uint(VXL_N * VXL_N * VXL_N);

void main() {
  // Groups past 32768 wrap into y (the least maximum per axis is 65535).
  uint i =
      (gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x) * 64u + gl_LocalInvocationIndex;
  if (i >= uBricks * kVoxels) return;
  uint e = usedSlots[i / kVoxels] * kVoxels + i % kVoxels;
  if (uPass == 0)
    kept[i] = pool[e];
  else
    pool[e] = kept[i];
}
