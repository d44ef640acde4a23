// SPDX-License-Identifier: BSD-3-Clause
// The walk inside one occupied brick (paper, section 3.1.4), row by row. A ray stays in a row
// (list) until it crosses a u or v plane; within that stretch the stored voxels it meets are the
// row's set mask bits between its entry and exit depths, taken in travel order, so the walk
// jumps from list element to list element instead of stepping through empty cells. Each stored
// voxel comes with the exact chord [tStart, tEnd) the ray spends in it.

struct RowWalk {
  Dda dda;       // voxel-cell walk, cell = the current row's entry cell
  ivec3 origin;  // the brick's first cell: rows and depths are brick-local
  ivec3 lo, hi;  // the cells walked: the brick's box of stored voxels (brick_bounds)
  uint k;        // occupied brick index
  uint base;     // its first voxel (BVOX)
  float t;       // where the ray entered the current row
  float tBrick;  // where it leaves the brick
  bool loaded;   // the row below is the current cell's
  Row row;
  uint hits;  // stored voxels of the row still ahead within this stretch
  int entryDepth;
  int depth;  // brick-local depth of the voxel returned last (the shadow cache's centre)
  float tRowEnd;
};

// Starts the walk at t through the cells [lo, hi] of occupied brick k (grid cell `brick`, first
// voxel `base`), which the ray leaves at tBrick.
RowWalk rowWalkBegin(vec3 o, vec3 d, float t, float tBrick, ivec3 brick, uint k, uint base,
                     ivec3 lo, ivec3 hi) {
  RowWalk w;
  w.origin = brick * VXL_N;
  w.lo = lo;
  w.hi = hi;
  w.dda = ddaInit(o, d, t, w.lo, w.hi);
  w.k = k;
  w.base = base;
  w.t = t;
  w.tBrick = tBrick;
  w.loaded = false;
  w.hits = 0u;
  return w;
}

// Number of crossings of the w planes strictly before tLimit.
int crossingsBefore(RowWalk w, float tLimit) {
  float tW = w.dda.tMax[VXL_W];
  if (w.dda.stepDir[VXL_W] == 0 || !(tW < tLimit)) return 0;
  return int(ceil((tLimit - tW) / w.dda.tDelta[VXL_W]));
}

// Next stored voxel on the ray inside the brick; false when the ray has left the brick.
bool rowWalkNext(inout RowWalk w, out uint voxel, out float tStart, out float tEnd) {
  for (int guard = 0; guard < 4 * VXL_N + 4; ++guard) {
    float tUV = min(w.dda.tMax[VXL_U], w.dda.tMax[VXL_V]);
    if (!w.loaded) {
      w.loaded = true;
      ivec3 local = w.dda.cell - w.origin;
      uint row = rowOfLocal(local);
      uvec2 info = rowInfo(w.k, row);  // one read for mask and start (bricks up to 16^3)
      w.row = Row(info.x, 0u);
      w.entryDepth = local[VXL_W];
      w.tRowEnd = min(tUV, w.tBrick);
      w.hits = 0u;
      if (w.row.bits != 0u) {
        // Depths from the entry depth to the last one reached before the row ends.
        int last = clamp(w.entryDepth + w.dda.stepDir[VXL_W] * crossingsBefore(w, w.tRowEnd),
                         w.lo[VXL_W] - w.origin[VXL_W], w.hi[VXL_W] - w.origin[VXL_W]);
        uint a = uint(min(w.entryDepth, last)), b = uint(max(w.entryDepth, last));
        uint upTo = b == 31u ? 0xFFFFFFFFu : (1u << (b + 1u)) - 1u;
        w.hits = w.row.bits & upTo & ~((1u << a) - 1u);
        // The row's first voxel, only for rows the ray meets voxels in.
        if (w.hits != 0u) w.row.first = rowFirst(w.base, info.y);
      }
    }
    if (w.hits != 0u) {
      int e = w.dda.stepDir[VXL_W] >= 0 ? findLSB(w.hits) : findMSB(w.hits);
      w.hits &= ~(1u << uint(e));
      int steps = abs(e - w.entryDepth);
      float tW = w.dda.tMax[VXL_W], dW = w.dda.tDelta[VXL_W];
      tStart = steps == 0 ? w.t : max(w.t, tW + float(steps - 1) * dW);
      tEnd = steps == 0 ? min(tW, w.tRowEnd) : min(tW + float(steps) * dW, w.tRowEnd);
      if (tStart >= w.tRowEnd) {
        w.hits = 0u;
      } else {
        voxel = uint(voxelInRow(w.row, uint(e)));
        w.depth = e;
        return true;
      }
      continue;
    }
    // Row done: move to the cell where the ray crosses the next u or v plane.
    if (tUV >= w.tBrick) return false;
    int m = crossingsBefore(w, tUV);
    w.dda.cell[VXL_W] += m * w.dda.stepDir[VXL_W];
    w.dda.tMax[VXL_W] += float(m) * w.dda.tDelta[VXL_W];
    if (w.dda.cell[VXL_W] < w.lo[VXL_W] || w.dda.cell[VXL_W] > w.hi[VXL_W]) return false;
    int axis = w.dda.tMax[VXL_U] < w.dda.tMax[VXL_V] ? VXL_U : VXL_V;
    ddaAdvance(w.dda, axis);
    if (w.dda.cell[axis] < w.lo[axis] || w.dda.cell[axis] > w.hi[axis]) return false;
    w.t = tUV;
    w.loaded = false;
  }
  return false;
}
