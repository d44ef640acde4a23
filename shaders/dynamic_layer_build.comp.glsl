// SPDX-License-Identifier: BSD-3-Clause
// Builds the dynamic layer (render/gl/gl_dynamic_layer.h) from the GL voxelizer's fragments, on
// the GPU: nothing is read back. The raster stage wrote each fragment with its column
// (uColumnInFragment) rather than into a list, so the passes (uPass) run one invocation per
// fragment, in any order:
//   3  one invocation: the dispatch size of the fragment passes from the fragment counter
//   0  per fragment: mark the brick of every voxel it covers
//   1  per brick: a marked brick takes the next pool slot (atomic) and zeroes its voxels
//   2  per fragment: add its triangle's area-weighted unit normal to its voxels in fixed point
//      (atomicAdd), and the triangle's material + 1 to .w (atomicMax)
// The per-voxel sum of area x unit normal is the host's mean rule (geometry/fragment_resolve.h)
// up to the fixed point; no depth sort is needed because a sum does not depend on order.
#version 450
layout(local_size_x = 64) in;

const uint kEmpty = 0xffffffffu;
const uint kMarked = 0xfffffffeu;
const float kFixedPoint = 4096.0;  // units per (voxel^2 of area x unit normal)

uniform int uPass;
uniform uint uColumns;     // viewport edge: columns per axis row
uniform uvec3 uDims;       // grid voxels
uniform uvec3 uBrickGrid;  // bricks per axis
uniform uint uBrickCapacity;
uniform uint uCapacity;  // fragment slots

layout(std430, binding = 1) readonly buffer Fragments { uvec4 fragments[]; };
layout(std430, binding = 2) readonly buffer Positions { float positions[]; };
layout(std430, binding = 3) readonly buffer Indices { uint indices[]; };
layout(std430, binding = 5) buffer BrickMap { uint brickMap[]; };
layout(std430, binding = 6) buffer Pool { ivec4 pool[]; };
layout(std430, binding = 8) readonly buffer TriangleMaterials { uint triangleMaterials[]; };
layout(std430, binding = 7) buffer Counters { uint brickCount; uint bricksDropped; };
layout(std430, binding = 9) readonly buffer FragmentCount { uint fragmentCount; };
layout(std430, binding = 10) writeonly buffer DispatchSize { uvec3 dispatchSize; };

vec3 vertexAt(uint v) {
  return vec3(positions[3u * v], positions[3u * v + 1u], positions[3u * v + 2u]);
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
  ivec3 add = ivec3(0);
  int material = 0;
  if (uPass == 2) {
    uint t = f.y;
    material = int(triangleMaterials[t]) + 1;
    vec3 a = vertexAt(indices[3u * t]);
    vec3 n = 0.5 * cross(vertexAt(indices[3u * t + 1u]) - a, vertexAt(indices[3u * t + 2u]) - a);
    float area = length(n);
    // Unit normal x area, the area clamped so a sum of 2^13 fragments fits an int.
    add = area > 0.0 ? ivec3(round(n / area * clamp(area, 1.0 / 256.0, 256.0) * kFixedPoint))
                     : ivec3(0);
  }
  for (uint k = f.x & 0xffffu; k <= (f.x >> 16u); ++k) {
    voxel[axis] = k;
    if (any(greaterThanEqual(voxel, uDims))) continue;
    uint b = brickIndex(voxel);
    if (uPass == 0) {
      brickMap[b] = kMarked;  // every writer stores the same value
    } else {
      uint s = brickMap[b];
      if (s == kEmpty) continue;  // a brick the pool had no room for (counted)
      uint e = s * uint(VXL_N * VXL_N * VXL_N) + voxelInBrick(voxel);
      atomicAdd(pool[e].x, add.x);
      atomicAdd(pool[e].y, add.y);
      atomicAdd(pool[e].z, add.z);
      atomicMax(pool[e].w, material);  // the highest material index of the voxel
    }
  }
}

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (uPass == 1) {
    if (i >= uBrickGrid.x * uBrickGrid.y * uBrickGrid.z || brickMap[i] != kMarked) return;
    uint s = atomicAdd(brickCount, 1u);
    if (s >= uBrickCapacity) {
      atomicAdd(bricksDropped, 1u);
      brickMap[i] = kEmpty;
      return;
    }
    brickMap[i] = s;
    uint base = s * uint(VXL_N * VXL_N * VXL_N);
    for (uint k = 0u; k < uint(VXL_N * VXL_N * VXL_N); ++k) pool[base + k] = ivec4(0);
    return;
  }
  if (uPass == 3) {
    if (i == 0u) dispatchSize = uvec3((min(fragmentCount, uCapacity) + 63u) / 64u, 1u, 1u);
    return;
  }
  if (i < min(fragmentCount, uCapacity)) addFragment(i);
}
