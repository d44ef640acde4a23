#version 450
// GL voxelization, fragment stage: a fragment at pixel centre (u + 0.5, v + 0.5) and depth d lies
// on its triangle inside voxel floor(d) of column (u, v). It is appended to that column's list,
// per-pixel-linked-list style: an atomic counter hands out the slot, an atomic exchange on the
// column's head pointer links it. The host sorts each list by depth.
noperspective in float vDepth;
flat in uint vTriangle;

uniform int uAxis;
uniform uvec3 uDims;  // voxels along u, v and the depth axis
uniform uint uColumns;  // heads per axis row (the viewport edge)
uniform uint uCapacity;  // fragment slots

layout(binding = 0, offset = 0) uniform atomic_uint fragmentCount;
layout(std430, binding = 0) coherent buffer Heads { uint heads[]; };  // 0xffffffff: empty
layout(std430, binding = 1) writeonly buffer Fragments {
  uvec4 fragments[];  // voxel along depth, triangle, next slot, depth bits
};

void main() {
  uint u = uint(gl_FragCoord.x), v = uint(gl_FragCoord.y);
  if (u >= uDims.x || v >= uDims.y || !(vDepth >= 0.0) || vDepth >= float(uDims.z)) return;
  uint slot = atomicCounterIncrement(fragmentCount);
  if (slot >= uCapacity) return;  // counted: the host grows the buffer and draws again
  uint column = (uint(uAxis) * uColumns + v) * uColumns + u;
  uint next = atomicExchange(heads[column], slot);
  fragments[slot] = uvec4(uint(floor(vDepth)), vTriangle, next, floatBitsToUint(vDepth));
}
