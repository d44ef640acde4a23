// Trilinear sampling of a VoxLink file. A sample at index-space point p blends the 8 voxels
// around q = p - 1/2 (voxel centres at integers). Samples are grouped by dual bricks (bricks
// shifted by half a voxel): dual brick D covers q in [D n, D n + n) and reads voxels of bricks
// D and D + 1 per axis, so it is skipped when those 8 bricks are all empty, and otherwise
// clipped to the union of their boxes of stored voxels (voxlink_brick_bounds.glsl) dilated by
// the reach of a sample. Corners are looked up in pairs along the predominant axis, so one row
// fetch serves both voxels of a pair.
// Mirrors ReferenceRenderer::traceTrilinear.

// Clips [t0, t1) to where samples of dual brick d can meet stored voxels: a sample at p blends
// the voxels of cells floor(p - 1/2) + {0, 1}, so a brick whose stored voxels fill the box
// [lo, hi] matters for p in (lo - 1/2, hi + 3/2). The bound is the union of that over the 8
// bricks dual brick d reads. False when none of them is occupied or the ray misses the union.
bool clipDualBrick(vec3 o, vec3 d, ivec3 dual, inout float t0, inout float t1) {
  vec3 lo = vec3(kBig), hi = vec3(-kBig);
  for (int i = 0; i < 8; ++i) {
    ivec3 b = dual + ivec3(i & 1, (i >> 1) & 1, (i >> 2) & 1);
    if (!insideGrid(b, uBrickGrid)) continue;
    int k = occupiedIndex(brickId(b));
    if (k < 0) continue;
    ivec3 blo, bhi;
    brickBox(uint(k), b, blo, bhi);
    lo = min(lo, vec3(blo));
    hi = max(hi, vec3(bhi));
  }
  if (lo.x > hi.x) return false;
  return clipToBox(o, d, lo - 0.5, hi + 1.5, t0, t1);
}

// The corner terms of a stored voxel (nothing for -1).
void storedCorner(int voxel, out vec4 colorAlpha, out vec3 gradient) {
  colorAlpha = vec4(0.0);
  gradient = vec3(0.0);
  if (voxel < 0) return;
  classifyCorner(storedBits(uint(voxel)), gradientCode(uint(voxel)), colorAlpha, gradient);
  gCellVisible = gCellVisible || colorAlpha.a > 0.0;
}

// The occupied index of the brick last looked up by pairIndices(): a cell's corners mostly share it.
uint gPairBrick;
int gPairK;

// Voxel indices (or -1) of corners 2j (depth w) and 2j + 1 (depth w + 1) of a cell whose
// corner 2j is voxel p. Both sit in one row (list) unless depth w is the brick's last, so one
// row fetch serves the pair. Indices first, classification after: llvmpipe runs divergent
// branches masked, so the expensive part is kept out of them.
void pairIndices(ivec3 p, out int first, out int second) {
  first = second = -1;
  ivec3 q = p;
  q[VXL_W] += 1;
  bool firstInside = insideGrid(p, uDims), secondInside = insideGrid(q, uDims);
  if (!firstInside && !secondInside) return;
  ivec3 base = firstInside ? p : q;
  ivec3 brick = base / VXL_N;
  uint id = brickId(brick);
  if (id != gPairBrick) {
    gPairBrick = id;
    gPairK = occupiedIndex(id);
  }
  ivec3 local = base - brick * VXL_N;
  uint depth = uint(local[VXL_W]);
  bool split = firstInside && secondInside && depth == uint(VXL_N - 1);
  if (gPairK >= 0) {
    Row row = fetchRow(uint(gPairK), rowOfLocal(local));
    int atDepth = voxelInRow(row, depth);
    if (firstInside) {
      first = atDepth;
      if (secondInside && !split) second = voxelInRow(row, depth + 1u);
    } else {
      second = atDepth;
    }
  }
  // The second voxel of a pair split by a brick face lives in the next brick's row.
  if (split) second = findVoxel(q);
}

// Voxel indices (or -1) of the pair in row `row` of occupied brick k at depths w, w + 1.
void rowPair(uint k, uint row, uint bits, uint depth, uint base, out int first, out int second) {
  first = second = -1;
  if ((bits & (3u << depth)) == 0u) return;
  uint r = k * uint(VXL_N * VXL_N) + row;
  Row fetched = Row(bits, base + u16At(rowsWord(r >> 1u), r));
  first = voxelInRow(fetched, depth);
  second = voxelInRow(fetched, depth + 1u);
}

// Corners are only read when gCellVisible ends up true, so an empty cell returns early without
// touching them.
void loadCorners(ivec3 cell) {
  gCellVisible = false;
  int v0, v1, v2, v3, v4, v5, v6, v7;
  ivec3 brick = cell / VXL_N;
  ivec3 local = cell - brick * VXL_N;
  if (all(greaterThanEqual(cell, ivec3(0))) && all(lessThan(local, ivec3(VXL_N - 1))) &&
      all(lessThan(cell + 1, uDims))) {
    // The common case, all 8 corners in one brick: one occupancy lookup and four row masks
    // (rows u, u + 1 by v, v + 1) decide whether the cell holds anything at all.
    int k = occupiedIndex(brickId(brick));
    if (k < 0) return;
    uint kk = uint(k);
    uint row = rowOfLocal(local);
    uint depth = uint(local[VXL_W]);
    uint b0 = rowBits(kk, row), b1 = rowBits(kk, row + 1u);
    uint b2 = rowBits(kk, row + uint(VXL_N)), b3 = rowBits(kk, row + uint(VXL_N) + 1u);
    if (((b0 | b1 | b2 | b3) & (3u << depth)) == 0u) return;
    uint base = bvoxWord(kk);
    rowPair(kk, row, b0, depth, base, v0, v1);
    rowPair(kk, row + 1u, b1, depth, base, v2, v3);
    rowPair(kk, row + uint(VXL_N), b2, depth, base, v4, v5);
    rowPair(kk, row + uint(VXL_N) + 1u, b3, depth, base, v6, v7);
  } else {
    // Corners spread over several bricks or past the volume's faces.
    gPairBrick = 0xFFFFFFFFu;
    pairIndices(cell + cornerOffset(0), v0, v1);
    pairIndices(cell + cornerOffset(2), v2, v3);
    pairIndices(cell + cornerOffset(4), v4, v5);
    pairIndices(cell + cornerOffset(6), v6, v7);
    if (max(max(max(v0, v1), max(v2, v3)), max(max(v4, v5), max(v6, v7))) < 0) return;
  }
  storedCorner(v0, gA0, gL0);
  storedCorner(v1, gA1, gL1);
  storedCorner(v2, gA2, gL2);
  storedCorner(v3, gA3, gL3);
  storedCorner(v4, gA4, gL4);
  storedCorner(v5, gA5, gL5);
  storedCorner(v6, gA6, gL6);
  storedCorner(v7, gA7, gL7);
}

// One flat loop: each pass either moves to the next dual brick or takes one sample. Nested
// loops (bricks, then samples) ran far slower on llvmpipe, whose SIMD lanes wait for the lane
// with the longest inner loop at every outer step.
void traceTrilinear(vec3 o, vec3 d, float t0, float t1, vec3 toEye, inout vec3 color,
                    inout float transmittance) {
  ivec3 dualGrid = (uDims - 1) / VXL_N + 2;  // dual bricks -1 .. floor((dims - 1) / n), shifted by 1
  Dda bricks = ddaInit((o - 0.5) / float(VXL_N) + 1.0, d / float(VXL_N), t0, ivec3(0), dualGrid - 1);
  float t = t0;  // where the ray entered the current dual brick
  int axis = minAxis(bricks.tMax);
  float tb = min(max(bricks.tMax[axis], t), t1);
  float tIn = t, tOut = tb;  // the part of the dual brick where samples can meet voxels
  bool brickActive = tb > t && clipDualBrick(o, d, bricks.cell - 1, tIn, tOut);
  int k = brickActive ? max(0, firstSampleNear(tIn, t0)) : 0;  // next sample t_k = t0 + (k + 1/2) step
  ivec3 cached = ivec3(-2147483647);
  int limit = dualGrid.x + dualGrid.y + dualGrid.z + int(min((t1 - t0) / uStep, 1e7)) + 8;
  for (int i = 0; i < limit; ++i) {
    float ts = t0 + (float(k) + 0.5) * uStep;
    if (!brickActive || ts >= tOut) {
      if (tb >= t1) return;
      t = tb;
      ddaAdvance(bricks, axis);
      if (bricks.cell[axis] < 0 || bricks.cell[axis] >= dualGrid[axis]) return;
      axis = minAxis(bricks.tMax);
      tb = min(max(bricks.tMax[axis], t), t1);
      tIn = t;
      tOut = tb;
      brickActive = tb > t && clipDualBrick(o, d, bricks.cell - 1, tIn, tOut);
      if (brickActive) k = max(k, firstSampleNear(tIn, t0));
      continue;
    }
    vec3 q = o + ts * d - 0.5;
    vec3 fl = floor(q);
    ivec3 cell = ivec3(fl);
    if (cell != cached) {
      cached = cell;
      loadCorners(cell);
    }
    if (!gCellVisible) {
      k = max(k + 1, firstSampleAfterCell(o, d, cell, t0));
      continue;
    }
    compositeSample(q, q - fl, toEye, color, transmittance);
    if (transmittance <= uStopTransmittance) return;
    ++k;
  }
}
