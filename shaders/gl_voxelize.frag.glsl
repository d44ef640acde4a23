#version 450
// SPDX-License-Identifier: BSD-3-Clause
// GL voxelization, fragment stage. Each fragment is appended to its (u, v) column's list,
// per-pixel-linked-list style: an atomic counter hands out the slot, an atomic exchange on the
// column's head pointer links it. The host sorts each list by depth.
//
// Plain (the paper): the fragment at pixel centre (u + 0.5, v + 0.5) and depth d lies on its
//   triangle inside voxel floor(d), so it marks that one voxel.
// uConservative: the part of the triangle over the pixel's square [u, u+1] x [v, v+1] is clipped
//   out (its depth is linear, so its extremes lie at triangle corners inside the square, square
//   corners inside the triangle, or edge crossings); it marks voxels floor(min)..floor(max) of
//   its depth range, and nothing when the triangle misses the square. Ties follow the exact path:
//   boxes are closed (a part that ends on a voxel face touches the voxel beyond it), except that
//   a triangle whose extent starts on the upper face of a voxel does not enter it.
noperspective in float vDepth;
flat in uint vTriangle;
flat in vec3 vCorner0, vCorner1, vCorner2;  // (u, v, depth), gl_voxelize.vert.glsl
flat in ivec4 vContribution;                // VXL_DYN_N: area x normal, material + 1

uniform int uAxis;
uniform uvec3 uDims;     // voxels along u, v and the depth axis
uniform uint uColumns;   // heads per axis row (the viewport edge)
uniform uint uCapacity;  // fragment slots
uniform bool uConservative;
// VXL_DYN_N defined (the brick edge): the dynamic layer (render/gl/gl_dynamic_layer.h). No list:
// each fragment adds its triangle's contribution (vContribution) to its voxels in a pool of
// bricks right here (atomics), the bricks found through a hash table of pool slots
// (shaders/dynamic_layer.glsl).

layout(binding = 0, offset = 0) uniform atomic_uint fragmentCount;
layout(std430, binding = 0) coherent buffer Heads { uint heads[]; };  // 0xffffffff: empty
layout(std430, binding = 1) writeonly buffer Fragments {
  uvec4 fragments[];  // first | last << 16 voxel along depth, triangle, next slot, depth bits
};
#ifdef VXL_DYN_N
#include "dynamic_layer.glsl"
#endif

// Depth range of the triangle over the square lo..lo+1; false when they do not meet. zMin: the
// triangle's lowest depth.
bool depthOverSquare(vec2 lo, out float dMin, out float dMax, out float zMin) {
  vec3 p[3] = vec3[3](vCorner0, vCorner1, vCorner2);
  vec2 hi = lo + 1.0;
  // Tie rule: an extent that starts on the square's upper edge does not enter it. A triangle
  // whose box ends before the square does not meet it either (the emulated conservative
  // raster's corners reach past thin triangles): those pixels skip the tests below.
  if (min(p[0].x, min(p[1].x, p[2].x)) >= hi.x || min(p[0].y, min(p[1].y, p[2].y)) >= hi.y ||
      max(p[0].x, max(p[1].x, p[2].x)) < lo.x || max(p[0].y, max(p[1].y, p[2].y)) < lo.y)
    return false;
  dMin = 1e30;
  dMax = -1e30;
  zMin = min(p[0].z, min(p[1].z, p[2].z));
  for (int i = 0; i < 3; ++i) {
    vec3 a = p[i], b = p[(i + 1) % 3];
    if (all(greaterThanEqual(a.xy, lo)) && all(lessThanEqual(a.xy, hi))) {
      dMin = min(dMin, a.z);
      dMax = max(dMax, a.z);
    }
    // Crossings of edge a-b with the square's four edge lines.
    for (int axis = 0; axis < 2; ++axis) {
      float delta = b[axis] - a[axis];
      if (delta == 0.0) continue;
      for (int side = 0; side < 2; ++side) {
        float t = ((side == 0 ? lo[axis] : hi[axis]) - a[axis]) / delta;
        if (t < 0.0 || t > 1.0) continue;
        vec3 q = mix(a, b, t);
        float other = q[1 - axis];
        if (other < lo[1 - axis] || other > hi[1 - axis]) continue;
        dMin = min(dMin, q.z);
        dMax = max(dMax, q.z);
      }
    }
  }
  // Square corners inside the triangle: depth from the plane.
  vec3 n = cross(p[1] - p[0], p[2] - p[0]);
  float s = sign(n.z);
  for (int k = 0; k < 4; ++k) {
    vec2 q = vec2((k & 1) == 0 ? lo.x : hi.x, (k & 2) == 0 ? lo.y : hi.y);
    bool inside = true;
    for (int i = 0; i < 3; ++i) {
      vec2 a = p[i].xy, b = p[(i + 1) % 3].xy;
      inside = inside && s * ((b.x - a.x) * (q.y - a.y) - (b.y - a.y) * (q.x - a.x)) >= 0.0;
    }
    if (inside) {
      float d = p[0].z - (n.x * (q.x - p[0].x) + n.y * (q.y - p[0].y)) / n.z;
      dMin = min(dMin, d);
      dMax = max(dMax, d);
    }
  }
  return dMin <= dMax;
}

void main() {
  uint u = uint(gl_FragCoord.x), v = uint(gl_FragCoord.y);
  if (u >= uDims.x || v >= uDims.y) return;
  float dMin = vDepth, dMax = vDepth, zMin = vDepth;
  if (uConservative && !depthOverSquare(vec2(u, v), dMin, dMax, zMin)) return;
  // On a voxel face, the part also touches the voxel below, unless the triangle starts there.
  float low = floor(dMin) == dMin && dMin > zMin ? dMin - 1.0 : floor(dMin);
  if (!(dMax >= 0.0) || low >= float(uDims.z)) return;
  uint first = uint(max(low, 0.0));
  uint last = min(uint(floor(dMax)), uDims.z - 1u);
#ifdef VXL_DYN_N
  uvec3 voxel;  // grid order x, y, z
  voxel[(uAxis + 1) % 3] = u;
  voxel[(uAxis + 2) % 3] = v;
  for (uint k = first; k <= last; ++k) {
    voxel[uAxis] = k;
    addToLayer(voxel, vContribution);
  }
#else
  uint slot = atomicCounterIncrement(fragmentCount);
  if (slot >= uCapacity) return;  // counted: the host grows the buffer and draws again
  uint column = (uint(uAxis) * uColumns + v) * uColumns + u;
  uint next = atomicExchange(heads[column], slot);
  fragments[slot] = uvec4(first | (last << 16), vTriangle, next, floatBitsToUint(dMin));
#endif
}
