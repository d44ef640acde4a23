#version 450
// SPDX-License-Identifier: BSD-3-Clause
// Test shader (tests/viewer/glsl_layout_test.cpp): looks up every cell of the volume the way
// the renderer does, so the test can compare with format::VoxelLocator and the file's arrays.
layout(local_size_x = 64) in;

uniform ivec3 uDims;

#include "common.glsl"
#include "voxlink_access.glsl"

// Per cell: voxel index or -1, stored value bits, the voxel word's direction bits
// (render/gl/detail/voxel_words.h), and the voxel found by the
// row walk's neighbour step (the next list element along the predominant axis) or -1.
layout(std430, binding = VXL_RESULTS_BINDING) writeonly restrict buffer Results { ivec4 results[]; };

void main() {
  uint i = gl_GlobalInvocationID.x;
  uint total = uint(uDims.x) * uint(uDims.y) * uint(uDims.z);
  if (i >= total) return;
  ivec3 p = ivec3(int(i % uint(uDims.x)), int((i / uint(uDims.x)) % uint(uDims.y)),
                  int(i / (uint(uDims.x) * uint(uDims.y))));
  int voxel = findVoxel(p);
  int bits = voxel >= 0 ? int(storedBits(uint(voxel))) : 0;
  int code = voxel >= 0 ? int(voxelWord(uint(voxel)) & 0xFFFFFFu) : 0;
  // The next stored voxel in the same row after depth w: rank of the next set bit.
  int next = -1;
  if (voxel >= 0) {
    ivec3 b = p / VXL_N;
    ivec3 local = p - b * VXL_N;
    Row row = fetchRow(uint(occupiedIndex(b)), rowOfLocal(local));
    uint later = row.bits & ~((2u << uint(local[VXL_W])) - 1u);
    if (local[VXL_W] == 31) later = 0u;
    if (later != 0u) next = voxelInRow(row, uint(findLSB(later)));
  }
  results[i] = ivec4(voxel, bits, code, next);
}
