// SPDX-License-Identifier: BSD-3-Clause
// The box each occupied brick's stored voxels fill (render/brick_bounds.h), derived when
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
// ray spends no time in the box. Written on whole vectors, without a loop over axes: as a loop
// (with its early exits) it cost about 340 instructions per call on llvmpipe.
bool clipToBox(vec3 o, vec3 d, vec3 lo, vec3 hi, inout float t0, inout float t1) {
  bvec3 parallel = lessThanEqual(abs(d), vec3(kParallelEpsilon));
  vec3 p = o + t0 * d;
  bvec3 outside = bvec3(uvec3(lessThan(p, lo)) | uvec3(greaterThanEqual(p, hi)));
  vec3 ta = (lo - o) / d, tb = (hi - o) / d;  // the parallel axes' values are not used
  vec3 tNear = mix(min(ta, tb), vec3(-kBig), parallel);
  vec3 tFar = mix(max(ta, tb), vec3(kBig), parallel);
  t0 = max(t0, max(max(tNear.x, tNear.y), tNear.z));
  t1 = min(t1, min(min(tFar.x, tFar.y), tFar.z));
  return !any(bvec3(uvec3(parallel) & uvec3(outside))) && t0 < t1;
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
