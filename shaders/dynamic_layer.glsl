// SPDX-License-Identifier: BSD-3-Clause
// Writing the dynamic layer (render/gl/gl_dynamic_layer.h) from gl_voxelize.frag.glsl: a voxel's
// brick gets its pool slot from a hash table (open addressing over the pool's slots, a slot's key
// is its brick + 1), so every fragment of a brick finds the same slot at once, without a pass
// that allocates first; the fragment that inserts a brick also writes the brick map (what the ray
// tracer reads) and lists the slot, which the next update zeroes (dynamic_layer_build.comp.glsl).
// VXL_DYN_N: the brick edge. VXL_DYN_POOLS: the pool's storage buffers (1-4; one binding holds
// at most GL_MAX_SHADER_STORAGE_BLOCK_SIZE bytes): slot s lives in buffer s / VXL_DYN_POOL_SLOTS.
const uint kDynEmpty = 0xffffffffu;    // brick map: no slot yet
const uint kDynDropped = 0xfffffffeu;  // brick map: no slot left (counted; the frame is an error)

uniform uvec3 uBrickGrid;     // bricks per axis (x, y, z)
uniform uint uBrickCapacity;  // pool slots, the hash table's size

layout(std430, binding = 5) buffer BrickMap { uint brickMap[]; };
layout(std430, binding = 6) buffer Pool { ivec4 pool[]; };  // normal sum xyz, material + 1
#if VXL_DYN_POOLS > 1
layout(std430, binding = 14) buffer Pool1 { ivec4 pool1[]; };
#endif
#if VXL_DYN_POOLS > 2
layout(std430, binding = 15) buffer Pool2 { ivec4 pool2[]; };
#endif
#if VXL_DYN_POOLS > 3
layout(std430, binding = 16) buffer Pool3 { ivec4 pool3[]; };
#endif
layout(std430, binding = 7) buffer Counters {
  uint usedSlotCount;
  uint bricksDropped;
};
layout(std430, binding = 11) buffer SlotKeys { uint slotKeys[]; };  // brick + 1; 0: free
layout(std430, binding = 12) writeonly buffer UsedSlots { uint usedSlots[]; };

// Brick b's pool slot, or kDynDropped. Keys are only added during an update, so the first slot
// of b's probe sequence that is free or holds b is the same for every fragment of b.
uint dynamicSlot(uint b) {
  uint known = brickMap[b];
  if (known != kDynEmpty) return known;
  uint h, low;  // the hash scaled to [0, capacity) by a multiply, not a division
  umulExtended(b * 2654435761u, uBrickCapacity, h, low);
  // Every slot may be tried: a brick is dropped only when the pool is full, and then once (the
  // map marks it), so a crowded table costs probes, never a spurious error.
  for (uint i = 0u; i < uBrickCapacity; ++i) {
    uint old = atomicCompSwap(slotKeys[h], 0u, b + 1u);
    if (old == 0u) {
      brickMap[b] = h;
      usedSlots[atomicAdd(usedSlotCount, 1u)] = h;
      return h;
    }
    if (old == b + 1u) return h;
    h = h + 1u == uBrickCapacity ? 0u : h + 1u;
  }
  if (atomicCompSwap(brickMap[b], kDynEmpty, kDynDropped) == kDynEmpty)
    atomicAdd(bricksDropped, 1u);
  return kDynDropped;
}

// Adds contribution c to element e of pool buffer P. The highest material index of the voxel; a
// stale read only costs the atomic.
#define VXL_DYN_ADD(P)                      \
  {                                         \
    atomicAdd(P[e].x, c.x);                 \
    atomicAdd(P[e].y, c.y);                 \
    atomicAdd(P[e].z, c.z);                 \
    if (P[e].w < c.w) atomicMax(P[e].w, c.w); \
  }

// Adds a triangle's contribution (area x unit normal in fixed point, material + 1) to a voxel.
void addToLayer(uvec3 voxel, ivec4 c) {
  const uint n = uint(VXL_DYN_N);
  uvec3 b = voxel / n;
  uint slot = dynamicSlot((b.z * uBrickGrid.y + b.y) * uBrickGrid.x + b.x);
  if (slot >= uBrickCapacity) return;
  uvec3 l = voxel % n;
#if VXL_DYN_POOLS > 1
  uint part = slot / uint(VXL_DYN_POOL_SLOTS);
  slot -= part * uint(VXL_DYN_POOL_SLOTS);
#endif
  uint e = slot * n * n * n + (l.z * n + l.y) * n + l.x;
#if VXL_DYN_POOLS > 3
  if (part == 3u) VXL_DYN_ADD(pool3) else
#endif
#if VXL_DYN_POOLS > 2
  if (part == 2u) VXL_DYN_ADD(pool2) else
#endif
#if VXL_DYN_POOLS > 1
  if (part == 1u) VXL_DYN_ADD(pool1) else
#endif
  VXL_DYN_ADD(pool)
}
