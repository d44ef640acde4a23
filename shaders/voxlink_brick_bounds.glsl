// The box each occupied brick's stored voxels fill (viewer/core/brick_bounds.h), derived when
// the file is loaded. Rays clip an occupied brick to it before walking rows, so they skip the
// empty part of a sparse brick, and the brick altogether when they miss its voxels. The box is
// the first word of the brick's entry (brickEntry(k)), its first voxel the second: one read
// gives both.

// The cells [lo, hi] (inclusive) of packed box word w of the brick at grid cell `brick`.
void unpackBrickBox(uint w, ivec3 brick, out ivec3 lo, out ivec3 hi) {
  ivec3 base = brick * VXL_N;
  lo = base + ivec3(w & 31u, (w >> 5u) & 31u, (w >> 10u) & 31u);
  hi = base + ivec3((w >> 15u) & 31u, (w >> 20u) & 31u, (w >> 25u) & 31u);
}

// Clips [t0, t1) to the part of the ray o + t d inside the box [lo, hi) (index space); on an axis
// the ray runs parallel to (ddaInit's rule), the point at t0 must lie inside. False when the
// ray spends no time in the box.
bool clipToBox(vec3 o, vec3 d, vec3 lo, vec3 hi, inout float t0, inout float t1) {
  for (int a = 0; a < 3; ++a) {
    if (abs(d[a]) <= kParallelEpsilon) {
      float p = o[a] + t0 * d[a];
      if (p < lo[a] || p >= hi[a]) return false;
      continue;
    }
    float ta = (lo[a] - o[a]) / d[a], tb = (hi[a] - o[a]) / d[a];
    t0 = max(t0, min(ta, tb));
    t1 = min(t1, max(ta, tb));
  }
  return t0 < t1;
}

// Clips [t0, t1) to the box of occupied brick k (grid cell `brick`); lo and hi get the box's
// cells (inclusive), base the brick's first voxel. False when the ray spends no time in the box.
bool clipToBrickBounds(vec3 o, vec3 d, uint k, ivec3 brick, inout float t0, inout float t1,
                       out ivec3 lo, out ivec3 hi, out uint base) {
  uvec2 entry = brickEntry(k);
  unpackBrickBox(entry.x, brick, lo, hi);
  base = entry.y;
  return clipToBox(o, d, vec3(lo), vec3(hi + 1), t0, t1);
}
