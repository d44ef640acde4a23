// SPDX-License-Identifier: BSD-3-Clause
// Voxel sampling of a scene (format version 2): the brick and row walks of voxlink_voxels.glsl
// over voxels with hits (voxlink_scene_shading.glsl, voxelHits). Included by voxlink_voxels.glsl
// when VXL_SCENE is 1.

// Composites the hits of one voxel: its geometry, then its volume sample; false when the ray
// stops there.
bool compositeVoxelHits(VoxelHits h, vec3 o, vec3 d, vec3 toEye, inout vec3 color,
                        inout float transmittance) {
  compositeGeometryHits(h, toEye, color, transmittance);
  if (transmittance <= uStopTransmittance) return false;
  if (h.volume)
    compositeVolumeSample(h.slot, h.word, h.c.rgb, h.a, o, d, h.ta, h.tz, toEye, color,
                          transmittance);
  return transmittance > uStopTransmittance;
}

#if VXL_EFFECTS || VXL_SHADOWS
// Where a hit casts shadow rays (and in the ray-traced mode loops over the lights and spawns
// rays), the walk stops at each voxel with hits, and the outer loop composites them and resumes
// the same walk: so the shading runs once per hit, outside the walk. llvmpipe runs every branch of
// a loop body for all 8 lanes of a SIMD vector in each pass; with the shading inside the row walk
// it ran once per voxel crossed, for each kind of hit (the glass bunny's ray-traced frame: 2.3x
// the shader instructions, docs/effects.md).
void traceVoxels(vec3 o, vec3 d, float t0, float t1, vec3 toEye, inout vec3 color,
                 inout float transmittance) {
  BrickWalk w = brickWalkBegin(o, d, t0, t1);
  RowWalk walk;
  bool inBrick = false;  // the row walk of the current brick goes on
  for (;;) {
    // The walk, on to the next voxel with hits.
    VoxelHits h;
    bool found = false;
    for (; brickWalkGoesOn(w);) {
      if (!inBrick) {
#if VXL_EFFECTS
        if (stopsForNextPass(w, o, d, toEye, transmittance)) return;
#endif
        inBrick = brickWalkEnter(w, o, d, true, walk);
      }
      while (inBrick) {
        uint voxel;
        float ta, tz;
        inBrick = rowWalkNext(walk, voxel, ta, tz);
        if (inBrick) found = voxelHits(voxel, o, d, ta, tz, h);
        if (found) break;
      }
      if (found || !brickWalkLeave(w)) break;
    }
    if (!found || !compositeVoxelHits(h, o, d, toEye, color, transmittance)) return;
  }
}
#else
// Without shadow rays a hit's shading is a few products: composited where the walk finds it
// (stopping the walk for it cost 12-13 % more shader instructions on the dragon and the foot on a
// mirror floor).
void traceVoxels(vec3 o, vec3 d, float t0, float t1, vec3 toEye, inout vec3 color,
                 inout float transmittance) {
  for (BrickWalk w = brickWalkBegin(o, d, t0, t1); brickWalkGoesOn(w);) {
    RowWalk walk;
    if (brickWalkEnter(w, o, d, true, walk)) {
      uint voxel;
      float ta, tz;
      while (rowWalkNext(walk, voxel, ta, tz)) {
        VoxelHits h;
        if (voxelHits(voxel, o, d, ta, tz, h) &&
            !compositeVoxelHits(h, o, d, toEye, color, transmittance))
          return;
      }
    }
    if (!brickWalkLeave(w)) break;
  }
}
#endif
