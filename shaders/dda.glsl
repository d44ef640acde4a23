// SPDX-License-Identifier: BSD-3-Clause
// Amanatides-Woo grid walk, used for bricks, dual bricks and voxels alike. Cells are unit cubes
// of the grid the caller scaled o and d into; t stays the caller's ray parameter.

struct Dda {
  ivec3 cell;
  ivec3 stepDir;
  vec3 tMax;    // t at which the ray leaves the cell across each axis
  vec3 tDelta;  // t between two crossings of each axis
};

// Starts at the cell holding o + t d, clamped into [lo, hi] against rounding at faces.
Dda ddaInit(vec3 o, vec3 d, float t, ivec3 lo, ivec3 hi) {
  Dda s;
  s.cell = clamp(ivec3(floor(o + t * d)), lo, hi);
  for (int a = 0; a < 3; ++a) {
    if (d[a] > kParallelEpsilon) {
      s.stepDir[a] = 1;
      s.tMax[a] = (float(s.cell[a] + 1) - o[a]) / d[a];
      s.tDelta[a] = 1.0 / d[a];
    } else if (d[a] < -kParallelEpsilon) {
      s.stepDir[a] = -1;
      s.tMax[a] = (float(s.cell[a]) - o[a]) / d[a];
      s.tDelta[a] = -1.0 / d[a];
    } else {
      s.stepDir[a] = 0;
      s.tMax[a] = kBig;
      s.tDelta[a] = kBig;
    }
  }
  return s;
}

void ddaAdvance(inout Dda s, int axis) {
  s.cell[axis] += s.stepDir[axis];
  s.tMax[axis] += s.tDelta[axis];
}
