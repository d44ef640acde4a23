// SPDX-License-Identifier: BSD-3-Clause
// Fills the per-voxel shadow cache before a frame (`--shadow-rays per-voxel`, docs/shadows.md):
// every stored voxel the transfer function leaves visible gets the transmittance from its
// centre towards the light, the same shadowTransmittance call the frame made on a miss. The
// frame then only reads codes (shadow_cache.glsl): no lane of a pixel's SIMD vector waits on
// another's shadow walk, and the walks run here one per invocation, side by side.
// One work group per occupied brick, one invocation per row. Few of a brick's cells hold a
// visible voxel (the foot at 256^3: a fifth of its occupied bricks' cells), so a walk per cell
// would leave most lanes of a SIMD vector idle while one walks: the group first lists its visible
// voxels in shared memory, then its invocations walk the list side by side. Depth n of a row is
// its apron copy (row_words.h), the voxel at depth 0 of the next brick along w. With
// VXL_SHADOW_MARKED it walks only the voxels the marking frame before it read (shadow_cache.glsl).
#version 450
layout(local_size_x = VXL_N, local_size_y = VXL_N) in;

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
#include "shadow_cache.glsl"

// Per occupied brick its grid cell (x, y, z), three words (render/gl/detail/shadow_cache_buffer.h).
layout(std430, binding = VXL_BRICK_CELLS_BINDING) readonly buffer BrickCells {
  uint bBrickCells[];
};
uniform uint uOccupiedBricks;
uniform uint uDepths;  // n, or n + 1 with row aprons

// The list holds up to 1024 voxels (8 KiB): the depths of one round fill it at most.
const uint kRows = uint(VXL_N * VXL_N);
const uint kRoundDepths = max(1024u / kRows, 1u);
shared uint sSlot[kRows * kRoundDepths];
shared uint sPlace[kRows * kRoundDepths];  // row | depth << 10
shared uint sCount;

void main() {
  uint k = gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x;
  if (k >= uOccupiedBricks) return;  // the whole group: barriers stay in uniform control flow
  const uint n = uint(VXL_N);
  uint row = gl_LocalInvocationIndex;
#if VXL_ROW_APRON
  uvec2 info = rowInfoWithApron(k, row);
#else
  uvec2 info = rowInfo(k, row);
#endif
  uint first = rowFirst(firstVoxel(k), info.y);
  ivec3 origin = ivec3(bBrickCells[3u * k], bBrickCells[3u * k + 1u], bBrickCells[3u * k + 2u]) *
                 VXL_N;
  for (uint d0 = 0u; d0 < uDepths; d0 += kRoundDepths) {
    if (row == 0u) sCount = 0u;
    barrier();
    for (uint depth = d0; depth < min(d0 + kRoundDepths, uDepths); ++depth) {
      if (((info.x >> depth) & 1u) == 0u) continue;
      uint before = depth == 0u ? 0u : uint(bitCount(info.x & ((1u << depth) - 1u)));
      uint slot = first + before;
#if VXL_SHADOW_MARKED
      if (!shadowMarked(slot)) continue;  // no sample of the frame reads it
#endif
      if (!(classify(storedBits(slot)).a > 0.0)) continue;
      uint i = atomicAdd(sCount, 1u);
      sSlot[i] = slot;
      sPlace[i] = row | depth << 10u;
    }
    barrier();
    uint count = sCount;
    for (uint i = row; i < count; i += kRows) {
      uint place = sPlace[i];
      ivec3 cell = origin;
      cell[VXL_W] += int(place >> 10u);
      cell[VXL_U] += int((place & 1023u) % n);
      cell[VXL_V] += int((place & 1023u) / n);
      storeShadowCode(sSlot[i], shadowCode(shadowTransmittance(indexToWorld(vec3(cell) + 0.5))));
    }
    barrier();  // sCount is reset for the next round
  }
}
