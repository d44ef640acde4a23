// SPDX-License-Identifier: BSD-3-Clause
// Builds the dynamic layer (render/gl/gl_dynamic_layer.h) from the GL voxelizer's fragments, on
// the GPU: nothing is read back. The raster stage wrote each fragment with its column
// (uColumnInFragment) rather than into a list, and gave every brick its fragments touch a pool
// slot (uBrickSize), so the passes (uPass) are:
//   3  one invocation: the dispatch sizes of passes 1 and 2 from the brick and fragment counters
//   1  per row of VXL_N voxels of the claimed bricks: zero it
//   2  per fragment: add its triangle's contribution (area-weighted unit normal in fixed point,
//      computed once per triangle on the host) to its voxels (atomicAdd), and the triangle's
//      material + 1 to .w (atomicMax, only where it raises it)
// The per-voxel sum of area x unit normal is the host's mean rule (geometry/fragment_resolve.h)
// up to the fixed point; no depth sort is needed because a sum does not depend on order.
#version 450
layout(local_size_x = 64) in;

uniform int uPass;
uniform uint uColumns;     // viewport edge: columns per axis row
uniform uvec3 uDims;       // grid voxels
uniform uvec3 uBrickGrid;  // bricks per axis
uniform uint uBrickCapacity;
uniform uint uCapacity;  // fragment slots

layout(std430, binding = 1) readonly buffer Fragments { uvec4 fragments[]; };
layout(std430, binding = 5) readonly buffer BrickMap { uint brickMap[]; };
layout(std430, binding = 6) buffer Pool { ivec4 pool[]; };
// Per triangle: area x unit normal in fixed point (xyz) and material + 1 (w).
layout(std430, binding = 8) readonly buffer Contributions { ivec4 contributions[]; };
layout(std430, binding = 7) readonly buffer Counters { uint brickCount; uint bricksDropped; };
layout(std430, binding = 9) readonly buffer FragmentCount { uint fragmentCount; };
// Indirect dispatch sizes: [0..2] pass 2 (per fragment), [4..6] pass 1 (per brick row).
layout(std430, binding = 10) writeonly buffer DispatchSizes { uint dispatchSizes[8]; };

// Groups of 64 for n invocations, wrapped into y past 32768 groups (the least maximum per axis is
// 65535).
void setGroups(uint at, uint n) {
  uint groups = (n + 63u) / 64u;
  dispatchSizes[at] = min(groups, 32768u);
  dispatchSizes[at + 1u] = (groups + 32767u) / 32768u;
  dispatchSizes[at + 2u] = 1u;
}

uint brickIndex(uvec3 voxel) {
  uvec3 b = voxel / uint(VXL_N);
  return (b.z * uBrickGrid.y + b.y) * uBrickGrid.x + b.x;
}

uint voxelInBrick(uvec3 voxel) {
  uvec3 l = voxel % uint(VXL_N);
  return (l.z * uint(VXL_N) + l.y) * uint(VXL_N) + l.x;
}

void addFragment(uint slot) {
  uvec4 f = fragments[slot];
  uint column = f.z;
  uint axis = column / (uColumns * uColumns);
  uvec3 voxel;
  voxel[(axis + 1u) % 3u] = column % uColumns;
  voxel[(axis + 2u) % 3u] = (column / uColumns) % uColumns;
  ivec4 add = contributions[f.y];
  for (uint k = f.x & 0xffffu; k <= (f.x >> 16u); ++k) {
    voxel[axis] = k;
    if (any(greaterThanEqual(voxel, uDims))) continue;
    uint s = brickMap[brickIndex(voxel)];
    if (s >= uBrickCapacity) continue;  // a brick the pool had no room for (counted)
    uint e = s * uint(VXL_N * VXL_N * VXL_N) + voxelInBrick(voxel);
    atomicAdd(pool[e].x, add.x);
    atomicAdd(pool[e].y, add.y);
    atomicAdd(pool[e].z, add.z);
    // The highest material index of the voxel; a stale read only costs the atomic.
    if (pool[e].w < add.w) atomicMax(pool[e].w, add.w);
  }
}

void main() {
  uint i = (gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x) * 64u +
           gl_LocalInvocationIndex;
  if (uPass == 3) {
    if (i != 0u) return;
    setGroups(0u, min(fragmentCount, uCapacity));
    setGroups(4u, min(brickCount, uBrickCapacity) * uint(VXL_N * VXL_N));
    return;
  }
  if (uPass == 1) {
    if (i >= min(brickCount, uBrickCapacity) * uint(VXL_N * VXL_N)) return;
    for (uint x = 0u; x < uint(VXL_N); ++x) pool[i * uint(VXL_N) + x] = ivec4(0);
    return;
  }
  if (i < min(fragmentCount, uCapacity)) addFragment(i);
}
