// SPDX-License-Identifier: BSD-3-Clause
// Shadow rays through a VoxLink file: transmittance towards the light with voxel (nearest)
// sampling, skipping empty bricks (voxlink_brick_walk.glsl) and, in an occupied one, stepping
// through the cells of its box of stored voxels (volumes) or walking its rows (scenes). Mirrors
// ReferenceRenderer::shadowTransmittance.

#include "voxlink_brick_walk.glsl"

// The cells of one occupied brick's box of stored voxels that a shadow ray crosses.
struct ShadowCells {
  Dda dda;
  ivec3 origin;  // the brick's first cell
  ivec3 lo, hi;  // the box (inclusive)
  uint k;        // occupied brick index
  uint base;     // its first voxel (BVOX)
  float t;       // where the ray enters the current cell
  float tOut;    // where it leaves the box
};

// Volumes (not scenes, below): adds the current cell's optical depth (unitOpticalDepth times
// its chord, in units of uUnit) to `depth` and steps on; false when the ray has left the box or
// the depth has passed `depthStop` (the light is all but gone). Straight-line
// code, called four times a loop pass: llvmpipe caps an invocation's loop passes (65535 for the
// 8 pixels of a SIMD vector, render/gl/detail/loop_limit_retrace.h), and a row walk's pass for
// every row change and voxel ran past it on a whole ray for one pixel alone (trilinear sampling,
// faint 80^3 volume). (Crossing a row's run of empty cells in the same step measured no faster
// on the foot and LIDC under this machine's load, so the walk stays simple.)
bool shadowCell(inout ShadowCells c, vec3 o, vec3 d, float depthStop, inout float depth) {
  if (!(c.t < c.tOut)) return false;
  ivec3 local = c.dda.cell - c.origin;
  uvec2 info = rowInfo(c.k, rowOfLocal(local));
  int voxel = voxelInRow(Row(info.x, rowFirst(c.base, info.y)), uint(local[VXL_W]));
  int axis = minAxis(c.dda.tMax);
  float tz = min(max(c.dda.tMax[axis], c.t), c.tOut);
  if (voxel >= 0) depth += (tz - c.t) * unitOpticalDepth(storedBits(uint(voxel)));
  c.t = tz;
  ddaAdvance(c.dda, axis);
  return depth <= depthStop && c.dda.cell[axis] >= c.lo[axis] && c.dda.cell[axis] <= c.hi[axis];
}

// Transmittance from worldPoint towards unit direction toLight, over at most `distance` (world;
// kBig for a directional light). The ray starts one voxel (uUnit) along its way, or
// the surface offset of fragment lists (VoxelSceneWalker::shadowStartOffset).
#if VXL_SURFACE_MODE == 0
const float kShadowStartVoxels = 1.0;
#elif VXL_SURFACE_MODE == 1
const float kShadowStartVoxels = 0.3;
#else
const float kShadowStartVoxels = 0.01;
#endif
float shadowAlong(vec3 worldPoint, vec3 toLight, float distance) {
  float start = kShadowStartVoxels * uUnit;
  vec3 o = worldToIndex(worldPoint + toLight * start);
  vec3 d = directionToIndex(toLight);
  vec2 range = intersectBox(o, d, vec3(uDims));
  float t0 = max(range.x, 0.0), t1 = min(range.y, distance - start);
  float transmittance = 1.0;
  if (!(t0 < t1)) return transmittance;
  // Volumes: the optical depth so far (world length times unitOpticalDepth), and where the
  // transmittance falls below uShadowStop.
  float depth = 0.0;
  const float depthStop = -log2(uShadowStop) * uUnit;
#if defined(VXL_DYNAMIC_LAYER) && VXL_SCENE
  // The moving meshes and spheres (voxlink_dynamic.glsl): each surface on the way to the light
  // lets its material's share through, as the primary ray composites each.
  transmittance = dynamicTransmittance(o, d, t0, t1);
  if (transmittance < uShadowStop) return transmittance;
#endif
  for (BrickWalk w = brickWalkBegin(o, d, t0, t1); brickWalkGoesOn(w);) {
#if VXL_SCENE
    // Scenes keep the row walk: their boxes of stored voxels hold thin surfaces, and the cell
    // walk (with geometryTransmittance four times over) doubled the CPU time of the
    // fragment-list scenes' test (FragmentListsRender.GlMatchesTheFloat64Walker, 17.6 s to
    // 30-36 s). The retrace pass (loop_limit_retrace.h) still guards them.
    RowWalk walk;
    if (brickWalkEnter(w, o, d, false, walk)) {
      uint voxel;
      float ta, tz;
      while (rowWalkNext(walk, voxel, ta, tz)) {
        transmittance *= geometryTransmittance(voxel, o, d, ta, tz);
        uint slot;
        if (!volumeSlot(voxel, slot)) continue;
        // VALU and GRAD of a scene hold the volume voxels only
        transmittance *= 1.0 - correctedAlpha(classify(storedBits(slot)).a, tz - ta);
        if (transmittance < uShadowStop) return transmittance;
      }
    }
#else
    ShadowCells c;
    if (brickWalkEnterBox(w, o, d, false, c.t, c.tOut, c.lo, c.hi, c.k, c.base)) {
      c.dda = ddaInit(o, d, c.t, c.lo, c.hi);
      c.origin = w.bricks.cell * VXL_N;
      for (;;) {
        if (!shadowCell(c, o, d, depthStop, depth) || !shadowCell(c, o, d, depthStop, depth) ||
            !shadowCell(c, o, d, depthStop, depth) || !shadowCell(c, o, d, depthStop, depth))
          break;
      }
      if (depth > depthStop) break;
    }
#endif
    if (!brickWalkLeave(w)) break;
  }
  return transmittance * exp2(-depth / uUnit);
}

// Towards the frame's directional light.
float shadowTransmittance(vec3 worldPoint) { return shadowAlong(worldPoint, uToLight, kBig); }
