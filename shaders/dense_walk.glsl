// SPDX-License-Identifier: BSD-3-Clause
// The dense peer's walk over every voxel the ray crosses, which its primary rays
// (dense_traversal.glsl) and shadow rays (dense_shadow.glsl) share:
//
//   for (DenseWalk w = denseWalkBegin(o, d, t0, t1); denseWalkGoesOn(w);) {
//     denseWalkEnter(w, cell, ta, tz);
//     ...
//     if (!denseWalkLeave(w)) break;
//   }
//
// The loop leaves through that break, not through a flag in its condition, as in
// voxlink_brick_walk.glsl: the flag changed some pixels on Mesa 22.3 llvmpipe.

struct DenseWalk {
  Dda voxels;
  float t;      // where the ray enters the current voxel
  float t1;     // where the walk ends
  float tExit;  // where it leaves the current voxel (at most t1)
  int axis;     // the axis it leaves the current voxel across
  int step;     // voxels visited so far
  int limit;    // more voxels than a ray crosses: a guard, never the reason a walk ends
};

// The walk of the ray o + t d (index space) over [t0, t1).
DenseWalk denseWalkBegin(vec3 o, vec3 d, float t0, float t1) {
  DenseWalk w;
  w.voxels = ddaInit(o, d, t0, ivec3(0), uDims - 1);
  w.t = t0;
  w.t1 = t1;
  w.tExit = t0;
  w.axis = 0;
  w.step = 0;
  w.limit = uDims.x + uDims.y + uDims.z + 3;
  return w;
}

bool denseWalkGoesOn(DenseWalk w) { return w.step < w.limit && w.t < w.t1; }

// The voxel the ray is in, `cell`, with the chord [tIn, tOut) the ray spends in it.
void denseWalkEnter(inout DenseWalk w, out ivec3 cell, out float tIn, out float tOut) {
  w.axis = minAxis(w.voxels.tMax);
  cell = w.voxels.cell;
  tIn = w.t;
  tOut = min(max(w.voxels.tMax[w.axis], w.t), w.t1);
  w.tExit = tOut;
}

// Steps on to the next voxel; false when the ray has left the grid.
bool denseWalkLeave(inout DenseWalk w) {
  w.t = w.tExit;
  ddaAdvance(w.voxels, w.axis);
  ++w.step;
  return w.voxels.cell[w.axis] >= 0 && w.voxels.cell[w.axis] < uDims[w.axis];
}
