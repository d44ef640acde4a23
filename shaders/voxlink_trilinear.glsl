// SPDX-License-Identifier: BSD-3-Clause
// Trilinear sampling of a VoxLink file. A sample at index-space point p blends the 8 voxels
// around q = p - 1/2 (voxel centres at integers). Samples are grouped by dual bricks (bricks
// shifted by half a voxel): dual brick D covers q in [D n, D n + n) and reads voxels of bricks
// D and D + 1 per axis, so it is skipped when the ray misses the box of its cells whose samples
// can meet a stored voxel (a table derived at load time); otherwise the samples within that box
// are taken. (Clipping to each of the 8 bricks' own boxes too saved a tenth of the loop's
// passes but cost 8 box clips per dual brick, which llvmpipe's lanes paid in most passes.)
// Corners are looked up in pairs along the predominant axis, so one row mask serves both
// voxels of a pair, and all through the occupied indices of the dual brick's 8
// bricks, found once when the ray enters it: a cell whose corners cross a brick face then takes
// the same path as any other cell (see loadCorners).
// Mirrors ReferenceRenderer::traceTrilinear.

// Occupied indices (or -1) of the bricks dual brick D reads, numbered like the corners of a cell
// (cornerOffset in compositing.glsl): bit 0 is brick D + 1 along w, bit 1 along u, bit 2 along v.
int gK0, gK1, gK2, gK3, gK4, gK5, gK6, gK7;
// Their first voxels (BVOX), 0 for -1; all 0 when row words hold file-wide indices
// (VXL_ROW_GLOBAL): no fetch on entering a dual brick and no select per corner then.
uint gB0, gB1, gB2, gB3, gB4, gB5, gB6, gB7;
ivec3 gDualBase;  // D n: the first cell of the dual brick, in index space
// After loadCorners: the cells [gRunLo, gRunHi) along w (dual-brick-local) around the current
// cell, in its u and v, that are known empty; just the cell itself when it is visible.
uint gRunLo, gRunHi;

// The run of empty cells along w around the empty cell at depth w < n - 1, from the mask bits
// `rows` of the four rows its corners lie in: cell w' < n - 1 is empty when bits w' and w' + 1
// are clear; the last cell's corners lie in the next brick, so a run stops before it. An empty
// cell then costs one pass of traceTrilinear's loop per run, not per cell (5 % fewer passes
// on the foot, firstSampleAfterRun).
void emptyRun(uint rows, uint w) {
  const uint last = uint(VXL_N - 1);
  uint filled = rows | (rows >> 1u) | (1u << last);
  uint below = (1u << w) - 1u;
  bool inside = w < last;
  gRunLo = inside ? uint(findMSB(filled & below) + 1) : w;
  gRunHi = inside ? uint(findLSB(filled & ~below)) : w + 1u;
}

// How far (voxels) rounding may put a sample outside its dual brick; see traceTrilinear.
const float kFaceTolerance = 0.01;

// Occupied index (or -1) of brick `dual + cornerOffset(m)` and its first voxel (0 for -1).
int dualBrickIndex(ivec3 dual, int m, out uint base) {
  int k = occupiedIndex(dual + cornerOffset(m));  // -1 outside the grid too
#if VXL_N <= 16 && VXL_ROW_GLOBAL
  base = 0u;
#else
  base = k < 0 ? 0u : firstVoxel(uint(k));
#endif
  return k;
}

#if VXL_DUAL_INDICES
// Occupied index (or -1) of brick m (numbered as cornerOffset) among the 16-bit indices `e` of
// a dual brick's bricks, which are numbered by x, y, z bits instead (brick_lookup.h); m is a
// constant, so the shifts fold.
int dualIndexOf(uvec4 e, int m) {
  ivec3 o = cornerOffset(m);
  int j = o.x + 2 * o.y + 4 * o.z;
  uint k = (e[j >> 1] >> (16u * uint(j & 1))) & 0xFFFFu;
  return k == 0xFFFFu ? -1 : int(k);
}
#endif

// Keeps the occupied indices and first voxels of the 8 bricks dual brick `dual` reads.
void loadDualBrick(ivec3 dual) {
#if VXL_DUAL_INDICES && VXL_N <= 16 && VXL_ROW_GLOBAL
  // One texel of the table derived at load time instead of 8 index lookups: a pass in which
  // any lane enters a dual brick runs this for all 8 lanes on llvmpipe. (dualBrickHit found
  // the dual cell dual + 1 inside the table.)
  ivec3 r = dual + 1 - kVxlDualLo;
  uvec4 e = dualIndexWords((uint(r.z) * uint(kVxlDualSize.y) + uint(r.y)) * uint(kVxlDualSize.x) +
                           uint(r.x));
  gK0 = dualIndexOf(e, 0);
  gK1 = dualIndexOf(e, 1);
  gK2 = dualIndexOf(e, 2);
  gK3 = dualIndexOf(e, 3);
  gK4 = dualIndexOf(e, 4);
  gK5 = dualIndexOf(e, 5);
  gK6 = dualIndexOf(e, 6);
  gK7 = dualIndexOf(e, 7);
  gB0 = gB1 = gB2 = gB3 = gB4 = gB5 = gB6 = gB7 = 0u;
#else
  gK0 = dualBrickIndex(dual, 0, gB0);
  gK1 = dualBrickIndex(dual, 1, gB1);
  gK2 = dualBrickIndex(dual, 2, gB2);
  gK3 = dualBrickIndex(dual, 3, gB3);
  gK4 = dualBrickIndex(dual, 4, gB4);
  gK5 = dualBrickIndex(dual, 5, gB5);
  gK6 = dualBrickIndex(dual, 6, gB6);
  gK7 = dualBrickIndex(dual, 7, gB7);
#endif
  gDualBase = dual * VXL_N;
}

// The corner terms of a stored voxel (nothing for -1). By selects, not early returns: each
// return became masking of every later write on llvmpipe (0.7 % of the tooth's instructions,
// docs/rendering-trilinear-profile.md, seventh session). -1 reads voxel 0, which is discarded.
void storedCorner(int voxel, out vec4 colorAlpha, out vec3 gradient) {
  uint index = uint(max(voxel, 0));
  uint word = voxelWord(index);  // value (8-bit files) and direction in one fetch
  vec4 c = classifyPremultiplied(storedBitsOf(index, word));
  bool visible = voxel >= 0 && c.a > 0.0;
  colorAlpha = visible ? c : vec4(0.0);
  gradient = visible ? scaledDirectionOfWord(word, c.a) : vec3(0.0);
  gCellVisible = gCellVisible || visible;
}

// Occupied index and first voxel of the dual brick's brick `m` (bits as in gK0..gK7), by
// selects, not branches.
void dualBrick(uint m, out int k, out uint base) {
  bool w = (m & 1u) != 0u, u = (m & 2u) != 0u, v = (m & 4u) != 0u;
  k = v ? (u ? (w ? gK7 : gK6) : (w ? gK5 : gK4)) : (u ? (w ? gK3 : gK2) : (w ? gK1 : gK0));
  base = v ? (u ? (w ? gB7 : gB6) : (w ? gB5 : gB4)) : (u ? (w ? gB3 : gB2) : (w ? gB1 : gB0));
}

// Mask bits and start (rowInfo) of row `row` of brick k, or 0 when k is -1 (the read then
// stays in bounds).
uvec2 rowInfoOrNone(int k, uint row) {
  return rowInfo(uint(max(k, 0)), row) & uvec2(k < 0 ? 0u : 0xFFFFFFFFu);
}

// Voxel indices (or -1) of a pair of corners: depth `depth` of row `a` in a brick whose first
// voxel is baseA and depth `next` of the same row in a brick with first voxel baseB (another
// brick where the pair crosses a w face).
void rowPair(uint baseA, uvec2 a, uint baseB, uvec2 b, uint depth, uint next, out int first,
             out int second) {
  first = ((a.x >> depth) & 1u) != 0u
              ? int(baseA + a.y + uint(bitCount(a.x & ((1u << depth) - 1u))))
              : -1;
  second = ((b.x >> next) & 1u) != 0u ? int(baseB + b.y + uint(bitCount(b.x & ((1u << next) - 1u))))
                                      : -1;
}

#if VXL_ROW_APRON
// rowInfoWithApron of row `row` of brick kA, which holds the first corner of a pair at depth w
// (0 when kA is -1). Where the pair crosses the w face (crossW) and kA is empty, brick kB next
// along w has no apron in kA to show its depth-0 voxel: its own row is read instead, that bit
// moved to w + 1. One fetch per pair either way.
uvec2 rowApronOrNone(int kA, int kB, bool crossW, uint row, uint w) {
  bool useNext = crossW && kA < 0;
  int k = useNext ? kB : kA;
  uvec2 a = rowInfoWithApron(uint(max(k, 0)), row) & uvec2(k < 0 ? 0u : 0xFFFFFFFFu);
  return useNext ? uvec2((a.x & 1u) << (w + 1u), a.y) : a;
}

// Voxel indices (or -1) of the pair of corners at depths w and w + 1 of a row with apron `a`.
void apronPair(uvec2 a, uint w, out int first, out int second) {
  uint index = a.y + uint(bitCount(a.x & ((1u << w) - 1u)));
  uint here = (a.x >> w) & 1u;
  first = here != 0u ? int(index) : -1;
  second = ((a.x >> (w + 1u)) & 1u) != 0u ? int(index + here) : -1;
}
#endif

// The row words of the current cell's corners (cellRows), kept for loadCorners: the pairs along
// w of rows (v, u), (v, u + 1), (v + 1, u), (v + 1, u + 1); the second of each pair only without
// row aprons, where the pair crosses the w face.
uvec2 gI0, gI1, gI2, gI3, gI4, gI5, gI6, gI7;

// The occupied indices and first voxels of cell-local corners 1..7 (corner 0's are gK0, gB0):
// where the cell's corners cross a brick face (`crossing`: bit 0 w, 1 u, 2 v), the dual brick's
// other bricks; by selects, not branches.
void cornerBricks(uint crossing, out int k1, out int k2, out int k3, out int k4, out int k5,
                  out int k6, out int k7, out uint s1, out uint s2, out uint s3, out uint s4,
                  out uint s5, out uint s6, out uint s7) {
  dualBrick(1u & crossing, k1, s1);
  dualBrick(2u & crossing, k2, s2);
  dualBrick(3u & crossing, k3, s3);
  dualBrick(4u & crossing, k4, s4);
  dualBrick(5u & crossing, k5, s5);
  dualBrick(6u & crossing, k6, s6);
  dualBrick(7u & crossing, k7, s7);
}

// The cell's position in the current dual brick: its depth w, row bits `crossing` (bit 0: the
// corners cross the w face, 1: the u face, 2: the v face) and its 4 rows r0..r3 as in cellRows.
// The cell lies in the current dual brick (traceTrilinear sees to it), so its corners sit in
// the 8 bricks looked up on entry; local coordinates wrap into the next brick.
void cellPlace(ivec3 cell, out uint w, out uint crossing, out uint r0, out uint r1, out uint r2,
               out uint r3) {
  ivec3 local = cell - gDualBase;
  const uint last = uint(VXL_N - 1);
  w = uint(local[VXL_W]);
  uint u = uint(local[VXL_U]), v = uint(local[VXL_V]);
  crossing = (w == last ? 1u : 0u) | (u == last ? 2u : 0u) | (v == last ? 4u : 0u);
  uint uNext = (u + 1u) & last, vNext = (v + 1u) & last;
  r0 = v * uint(VXL_N) + u;
  r1 = v * uint(VXL_N) + uNext;
  r2 = vNext * uint(VXL_N) + u;
  r3 = vNext * uint(VXL_N) + uNext;
}

// Reads the row words of the cell's corners (gI0..gI7): true when some corner is a stored voxel.
// Otherwise [gRunLo, gRunHi) is the run of empty cells along w around it that the rows' masks
// show. Row words alone: traceTrilinear crosses empty cells with this, and only a cell with a
// stored corner goes on to loadCorners' voxel-word and TF fetches.
bool cellRows(ivec3 cell) {
  uint w, crossing, r0, r1, r2, r3;
  cellPlace(cell, w, crossing, r0, r1, r2, r3);
  gRunLo = w;  // a cell with stored corners is its own run
  gRunHi = w + 1u;
  int k1, k2, k3, k4, k5, k6, k7;
  uint s1, s2, s3, s4, s5, s6, s7;
  cornerBricks(crossing, k1, k2, k3, k4, k5, k6, k7, s1, s2, s3, s4, s5, s6, s7);
#if VXL_ROW_APRON
  // Each pair along w in one row word: its second corner is bit w + 1, the apron bit (the next
  // brick's depth 0) where the pair crosses the w face, and it follows the first in the voxel
  // words (row_words.h): 4 fetches per cell, not 8.
  bool crossW = (crossing & 1u) != 0u;
  gI0 = rowApronOrNone(gK0, k1, crossW, r0, w);
  gI2 = rowApronOrNone(k2, k3, crossW, r1, w);
  gI4 = rowApronOrNone(k4, k5, crossW, r2, w);
  gI6 = rowApronOrNone(k6, k7, crossW, r3, w);
  uint rows = gI0.x | gI2.x | gI4.x | gI6.x;
  if (((rows >> w) & 3u) != 0u) return true;
  emptyRun(rows & ((1u << uint(VXL_N)) - 1u), w);
#else
  uint wNext = (w + 1u) & uint(VXL_N - 1);
  gI0 = rowInfoOrNone(gK0, r0);
  gI2 = rowInfoOrNone(k2, r1);
  gI4 = rowInfoOrNone(k4, r2);
  gI6 = rowInfoOrNone(k6, r3);
  gI1 = gI0;
  gI3 = gI2;
  gI5 = gI4;
  gI7 = gI6;
  if ((crossing & 1u) != 0u) {  // the pairs' second corners lie in the next brick along w
    gI1 = rowInfoOrNone(k1, r0);
    gI3 = rowInfoOrNone(k3, r1);
    gI5 = rowInfoOrNone(k5, r2);
    gI7 = rowInfoOrNone(k7, r3);
  }
  uint hits = ((gI0.x | gI2.x | gI4.x | gI6.x) >> w) | ((gI1.x | gI3.x | gI5.x | gI7.x) >> wNext);
  if ((hits & 1u) != 0u) return true;
  emptyRun(gI0.x | gI2.x | gI4.x | gI6.x, w);
#endif
  return false;
}

// Loads the corners of a cell that cellRows found to have a stored corner, from its row words;
// gCellVisible tells whether the TF leaves some corner visible. llvmpipe runs both sides of a
// branch whenever its lanes disagree, so there is one path for every cell: a separate one for
// cells whose corners cross a brick face (1 - (1 - 1/n)^3 of them) ran in most SIMD vectors and
// took a third of the frame's instructions.
void loadCorners(ivec3 cell) {
  gCellVisible = false;
  int v0, v1, v2, v3, v4, v5, v6, v7;
  uint w, crossing, r0, r1, r2, r3;
  cellPlace(cell, w, crossing, r0, r1, r2, r3);
#if VXL_ROW_APRON
  apronPair(gI0, w, v0, v1);
  apronPair(gI2, w, v2, v3);
  apronPair(gI4, w, v4, v5);
  apronPair(gI6, w, v6, v7);
#else
  int k1, k2, k3, k4, k5, k6, k7;
  uint s1, s2, s3, s4, s5, s6, s7;
  cornerBricks(crossing, k1, k2, k3, k4, k5, k6, k7, s1, s2, s3, s4, s5, s6, s7);
  uint wNext = (w + 1u) & uint(VXL_N - 1);
  rowPair(gB0, gI0, s1, gI1, w, wNext, v0, v1);
  rowPair(s2, gI2, s3, gI3, w, wNext, v2, v3);
  rowPair(s4, gI4, s5, gI5, w, wNext, v4, v5);
  rowPair(s6, gI6, s7, gI7, w, wNext, v6, v7);
#endif
  storedCorner(v0, gA0, gL0);
  storedCorner(v1, gA1, gL1);
  storedCorner(v2, gA2, gL2);
  storedCorner(v3, gA3, gL3);
  storedCorner(v4, gA4, gL4);
  storedCorner(v5, gA5, gL5);
  storedCorner(v6, gA6, gL6);
  storedCorner(v7, gA7, gL7);
#if VXL_SHADOWS && VXL_SHADOW_CACHE
  loadCornerShadows(v0, v1, v2, v3, v4, v5, v6, v7, gA0.a, gA1.a, gA2.a, gA3.a, gA4.a, gA5.a,
                    gA6.a, gA7.a);  // shadow_cache.glsl
#endif
}

// Whether the ray's samples in [t0, t1) can meet a stored voxel in the dual brick at cell c of
// the dual grid (dual brick c - 1), and [t0, t1) clipped to where they can: one word of the
// table derived at load time (render/brick_lookup.h), the box of the dual brick's cells that can.
bool dualBrickHit(vec3 o, vec3 d, ivec3 c, inout float t0, inout float t1) {
  // The table covers the dual cells around the occupied bricks (kVxlDualLo/kVxlDualSize).
  ivec3 r = c - kVxlDualLo;
  if (any(lessThan(r, ivec3(0))) || any(greaterThanEqual(r, kVxlDualSize))) return false;
  uint i = (uint(r.z) * uint(kVxlDualSize.y) + uint(r.y)) * uint(kVxlDualSize.x) + uint(r.x);
  uint box = dualBoxWord(i);
  if (box == 0xFFFFFFFFu) return false;
  ivec3 lo, hi;
  unpackBrickBox(box, c - 1, lo, hi);  // cells; cell c covers p in [c + 1/2, c + 3/2)
  // Widened like the samples that rounding leaves outside their dual brick (traceTrilinear).
  return clipToBox(o, d, vec3(lo) + (0.5 - kFaceTolerance), vec3(hi) + (1.5 + kFaceTolerance), t0,
                   t1);
}

// The cell of the sample at ts and its point qIn (q = p - 1/2), moved into the current dual
// brick: rounding can leave a sample of a dual brick a hair outside it (a cell at the far face
// takes fraction 1). False when it lies further out than kFaceTolerance: the sample before tIn
// may lie in the previous dual brick, where that brick's clip found nothing to meet; skipped.
bool placeSample(vec3 o, vec3 d, float ts, out vec3 qIn, out ivec3 cell) {
  vec3 q = o + ts * d - 0.5;
  qIn = clamp(q, vec3(gDualBase), vec3(gDualBase + VXL_N));
  cell = min(ivec3(floor(qIn)), gDualBase + (VXL_N - 1));
  return all(lessThanEqual(abs(qIn - q), vec3(kFaceTolerance)));
}

// Index of the first sample t_k = t0 + (k + 1/2) step at or after the ray leaves the empty cell
// `cell` and its run along w (as firstSampleAfterCell in compositing.glsl).
int firstSampleAfterRun(vec3 o, vec3 d, ivec3 cell, float t0) {
  vec3 lo = vec3(cell), hi = vec3(cell + 1);
  lo[VXL_W] = float(gDualBase[VXL_W] + int(gRunLo));
  hi[VXL_W] = float(gDualBase[VXL_W] + int(gRunHi));
  float tExit = kBig;
  for (int a = 0; a < 3; ++a) {
    if (abs(d[a]) < kParallelEpsilon) continue;
    tExit = min(tExit, ((d[a] > 0.0 ? hi[a] : lo[a]) + 0.5 - o[a]) / d[a]);
  }
  return int(ceil((tExit - t0) / uStep - 0.5));
}

// One flat loop: each pass moves to the next dual brick where needed, crosses runs of empty
// cells on row words and takes the samples of one cell. Nested loops (bricks, then samples) ran
// far slower on llvmpipe, whose SIMD lanes wait for the lane with the longest inner loop at
// every outer step; the empty-cell loop is cheap per step (row words only).
void traceTrilinear(vec3 o, vec3 d, float t0, float t1, vec3 toEye, inout vec3 color,
                    inout float transmittance) {
  ivec3 dualGrid =
      (uDims - 1) / VXL_N + 2;  // dual bricks -1 .. floor((dims - 1) / n), shifted by 1
  Dda bricks =
      ddaInit((o - 0.5) / float(VXL_N) + 1.0, d / float(VXL_N), t0, ivec3(0), dualGrid - 1);
  float t = t0;  // where the ray entered the current dual brick
  int axis = minAxis(bricks.tMax);
  float tb = min(max(bricks.tMax[axis], t), t1);
  float tIn = t, tOut = tb;  // the part of the dual brick where samples can meet voxels
  bool brickActive = tb > t && dualBrickHit(o, d, bricks.cell, tIn, tOut);
  if (brickActive) loadDualBrick(bricks.cell - 1);
  int k =
      brickActive ? max(0, firstSampleNear(tIn, t0)) : 0;  // next sample t_k = t0 + (k + 1/2) step
  ivec3 cached = ivec3(-2147483647);
  bool leave = false;  // the cell at sample k is to be left: invisible under the TF
  int limit = dualGrid.x + dualGrid.y + dualGrid.z + int(min((t1 - t0) / uStep, 1e7)) + 8;
  for (int i = 0; i < limit; ++i) {
    float ts = t0 + (float(k) + 0.5) * uStep;
    if (!brickActive || ts >= tOut) {
      // On to the next dual brick, crossing runs of empty ones here (llvmpipe runs the whole
      // loop body for all lanes whenever one lane needs a part of it, see voxlink_voxels.glsl).
      bool outside = false;
      for (int j = 0; j < limit; ++j) {
        if (tb >= t1) {
          outside = true;
          break;
        }
        t = tb;
        ddaAdvance(bricks, axis);
        if (bricks.cell[axis] < 0 || bricks.cell[axis] >= dualGrid[axis]) {
          outside = true;
          break;
        }
        axis = minAxis(bricks.tMax);
        tb = min(max(bricks.tMax[axis], t), t1);
        tIn = t;
        tOut = tb;
        if (dualBrickHit(o, d, bricks.cell, tIn, tOut)) break;
      }
      if (outside) return;
      brickActive = true;
      loadDualBrick(bricks.cell - 1);
      // The same pass goes on to the dual brick's first sample: every pass runs both halves of
      // this loop's body on llvmpipe, so a pass that only entered a dual brick was half wasted.
      k = max(k, firstSampleNear(tIn, t0));
      ts = t0 + (float(k) + 0.5) * uStep;
      if (ts >= tOut) continue;
    }
    vec3 qIn;
    ivec3 cell;
    if (!placeSample(o, d, ts, qIn, cell)) {
      ++k;
      continue;
    }
    if (cell != cached || leave) {
      // Runs of empty cells are crossed here, on row words alone (4 fetches per run), until a
      // cell with a stored corner: on llvmpipe a pass of this loop runs its whole body, 24
      // fetches, for all 8 lanes, and a pass per empty run was a third of the tooth's passes.
      // The samples taken are the ones a pass per run would take.
      bool stored = false;
      for (;;) {
        if (!leave) {
          stored = cellRows(cell);
          if (stored) break;
        }
        leave = false;
        k = max(k + 1, firstSampleAfterRun(o, d, cell, t0));
        ts = t0 + (float(k) + 0.5) * uStep;
        if (ts >= tOut) break;  // the next pass moves on to the next dual brick
        if (!placeSample(o, d, ts, qIn, cell)) {
          ++k;
          break;
        }
      }
      if (!stored) continue;
      cached = cell;
      loadCorners(cell);
    }
    if (!gCellVisible) {
      // Stored corners that the TF leaves invisible: the next pass's loop above leaves the cell,
      // so that the body holds one firstSampleAfterRun, not two (the pass count is the same).
      leave = true;
      continue;
    }
    // Every sample of a visible cell in this pass: its corners are loaded, and a pass of this
    // loop runs the whole body (corner lookup included) on llvmpipe, while this inner loop runs
    // only the blend and shading. The samples taken are the ones the outer loop would take.
    for (;;) {
      compositeSample(qIn, qIn - vec3(cell), toEye, color, transmittance);
      if (transmittance <= uStopTransmittance) return;
      ++k;
      ts = t0 + (float(k) + 0.5) * uStep;
      qIn = o + ts * d - 0.5;
      if (ts >= tOut || any(notEqual(ivec3(floor(qIn)), cell))) break;
    }
  }
}
