// SPDX-License-Identifier: BSD-3-Clause
// Marks the moving spheres of a dynamic scene (render/gl/gl_dynamic_spheres.h): one invocation
// per sphere appends it to the list of every brick (VXL_N voxels) its ball, grown by uMargin
// voxels, touches. A list is a head per brick and nodes (sphere, next) taken from one counter;
// a reference past the room is dropped and counted (the update is then an error). Nothing is
// read back.
#version 450
layout(local_size_x = 64) in;

const uint kEmpty = 0xffffffffu;

uniform uint uFirstSphere;  // this pass marks spheres uFirstSphere.. (the others are kept)
uniform uint uSphereCount;
uniform uint uCapacity;
uniform vec3 uOrigin;  // world of voxel 0's centre
uniform float uSpacing;
uniform float uMargin;
uniform ivec3 uBrickGrid;

layout(std430, binding = 0) readonly buffer Spheres { float spheres[]; };  // 8 words each
layout(std430, binding = 1) buffer Heads { uint heads[]; };
layout(std430, binding = 2) writeonly buffer Nodes { uvec2 nodes[]; };
layout(std430, binding = 3) buffer Counters {
  uint referenceCount;
  uint referencesDropped;
};

void main() {
  uint i = (gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x) * 64u +
           gl_LocalInvocationIndex;
  if (i >= uSphereCount) return;
  uint s = uFirstSphere + i;
  // Index space as the ray tracer's worldToIndex: voxel i spans [i, i + 1).
  vec3 c = (vec3(spheres[s * 8u], spheres[s * 8u + 1u], spheres[s * 8u + 2u]) - uOrigin) /
               uSpacing +
           0.5;
  float r = spheres[s * 8u + 3u] / uSpacing + uMargin;
  const int n = VXL_N;
  ivec3 bLo = clamp(ivec3(floor((c - r) / float(n))), ivec3(0), uBrickGrid - 1);
  ivec3 bHi = clamp(ivec3(floor((c + r) / float(n))), ivec3(0), uBrickGrid - 1);
  for (int z = bLo.z; z <= bHi.z; ++z)
    for (int y = bLo.y; y <= bHi.y; ++y)
      for (int x = bLo.x; x <= bHi.x; ++x) {
        // The ball against the brick's box: the box's nearest point within r.
        vec3 lo = vec3(ivec3(x, y, z) * n);
        vec3 nearest = clamp(c, lo, lo + float(n));
        vec3 gap = c - nearest;
        if (dot(gap, gap) > r * r) continue;
        uint node = atomicAdd(referenceCount, 1u);
        if (node >= uCapacity) {
          atomicAdd(referencesDropped, 1u);
          continue;
        }
        uint b = uint((z * uBrickGrid.y + y) * uBrickGrid.x + x);
        nodes[node] = uvec2(s, atomicExchange(heads[b], node));
      }
}
