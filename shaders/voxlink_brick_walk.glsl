// SPDX-License-Identifier: BSD-3-Clause
// The walk over the brick grid that voxel sampling (voxlink_voxels.glsl) and shadow rays
// (voxlink_shadow.glsl) share: it steps from brick to brick (crossing runs of empty ones in an
// inner loop where asked), clips each occupied brick to the box of its stored voxels
// (voxlink_brick_bounds.glsl) and starts the row walk there (voxlink_row_walk.glsl), from which
// the caller takes the stored voxels:
//
//   for (BrickWalk w = brickWalkBegin(o, d, t0, t1); brickWalkGoesOn(w);) {
//     RowWalk rows;
//     if (brickWalkEnter(w, o, d, skipEmpty, rows))
//       while (rowWalkNext(rows, voxel, ta, tz)) ...
//     if (!brickWalkLeave(w)) break;
//   }
//
// The loop leaves through that break, not through a flag in its condition: with the flag, Mesa
// 22.3 llvmpipe rendered some shadows differently (up to 67/255 in 290 pixels of the foot CT
// with --shadows at 384x384), though the walk is the same. The cause was llvmpipe's cap on an
// invocation's loop passes, which a different loop shape reached elsewhere
// (render/gl/detail/loop_limit_retrace.h).

struct BrickWalk {
  Dda bricks;
  float t;       // where the ray enters the current brick
  float t1;      // where the walk ends
  float tExit;   // where it leaves the current brick (at most t1)
  int axis;      // the axis it leaves the current brick across
  int step;      // passes so far; a run of empty bricks crossed in one counts as none
  int limit;     // more bricks than a ray crosses: a guard, never the reason a walk ends
  bool outside;  // the ray left the grid or passed t1 while crossing empty bricks
};

// The walk of the ray o + t d (index space) over [t0, t1).
BrickWalk brickWalkBegin(vec3 o, vec3 d, float t0, float t1) {
  BrickWalk w;
  w.bricks = ddaInit(o / float(VXL_N), d / float(VXL_N), t0, ivec3(0), uBrickGrid - 1);
  w.t = t0;
  w.t1 = t1;
  w.tExit = t0;
  w.axis = 0;
  w.step = 0;
  w.limit = uBrickGrid.x + uBrickGrid.y + uBrickGrid.z + 3;
  w.outside = false;
  return w;
}

bool brickWalkGoesOn(BrickWalk w) { return w.step < w.limit && w.t < w.t1; }

// Clips the ray to the box of stored voxels of the brick it is in: [tIn, tOut), the box's cells
// lo..hi, the brick's occupied index k and first voxel base; false when the brick is empty or the
// ray misses its voxels. With `skipEmpty` (a constant at each call, folded away) a run of empty
// bricks ahead is crossed first, in an inner loop; false too when the ray leaves the grid or
// passes t1 there.
bool brickWalkEnterBox(inout BrickWalk w, vec3 o, vec3 d, bool skipEmpty, out float tIn,
                       out float tOut, out ivec3 lo, out ivec3 hi, out uint k, out uint base) {
  int axis = minAxis(w.bricks.tMax);
  int occupied = occupiedIndex(w.bricks.cell);
  if (skipEmpty) {
    // Runs of empty bricks are crossed here, one occupancy bit each: llvmpipe executes the
    // whole body of the caller's loop for all 8 lanes of a SIMD vector whenever one of them
    // needs it, so an empty brick taking a pass of its own costs as much as an occupied one.
    // Shadow rays do without it: there it changed the images on Mesa 22.3 llvmpipe (up to
    // 76/255 in 810 pixels of the foot CT with --shadows at 384x384), though the walk is the
    // same: llvmpipe's cap on loop passes (render/gl/detail/loop_limit_retrace.h), now handled.
    for (int j = 0; j < w.limit && occupied < 0; ++j) {
      w.t = min(max(w.bricks.tMax[axis], w.t), w.t1);
      ddaAdvance(w.bricks, axis);
      if (w.t >= w.t1 || w.bricks.cell[axis] < 0 || w.bricks.cell[axis] >= uBrickGrid[axis]) {
        w.outside = true;  // (a return from inside this loop gave wrong images on Mesa 22.3)
        break;
      }
      axis = minAxis(w.bricks.tMax);
      occupied = occupiedIndex(w.bricks.cell);
    }
    if (w.outside) return false;
  }
  w.axis = axis;
  w.tExit = min(max(w.bricks.tMax[axis], w.t), w.t1);
  tIn = w.t;
  tOut = w.tExit;
  k = uint(max(occupied, 0));
  return occupied >= 0 && w.tExit > w.t &&
         clipToBrickBounds(o, d, k, w.bricks.cell, tIn, tOut, lo, hi, base);
}

// brickWalkEnterBox, then the row walk `rows` through the box's stored voxels.
bool brickWalkEnter(inout BrickWalk w, vec3 o, vec3 d, bool skipEmpty, out RowWalk rows) {
  float tIn, tOut;
  ivec3 lo, hi;
  uint k, base;
  if (!brickWalkEnterBox(w, o, d, skipEmpty, tIn, tOut, lo, hi, k, base)) return false;
  rows = rowWalkBegin(o, d, tIn, tOut, w.bricks.cell, k, base, lo, hi);
  return true;
}

// Steps on to the next brick; false when the ray has left the grid.
bool brickWalkLeave(inout BrickWalk w) {
  if (w.outside) return false;
  w.t = w.tExit;
  ddaAdvance(w.bricks, w.axis);
  ++w.step;
  return w.bricks.cell[w.axis] >= 0 && w.bricks.cell[w.axis] < uBrickGrid[w.axis];
}
