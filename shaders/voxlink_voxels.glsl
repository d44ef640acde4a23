// SPDX-License-Identifier: BSD-3-Clause
// Voxel (nearest) sampling of a VoxLink file (paper, section 3.1.4): a walk over bricks skips
// unoccupied ones (voxlink_brick_walk.glsl); inside an occupied brick the row walk
// (voxlink_row_walk.glsl) visits the stored voxels along the lists. Each stored voxel
// contributes over the exact chord the ray spends in it. Mirrors ReferenceRenderer::traceVoxels.

#include "voxlink_brick_walk.glsl"

// Composites the volume sample of stored voxel `voxel` (its voxel word, classified colour c and
// opacity a > 0 over the chord [ta, tz)).
void compositeVolumeSample(uint voxel, uint word, vec3 c, float a, vec3 o, vec3 d, float ta,
                           float tz, vec3 toEye, inout vec3 color, inout float transmittance) {
#if VXL_EFFECTS
  color += transmittance * a *
           effectsVolumeShade(c, directionOfWord(word), indexToWorld(o + 0.5 * (ta + tz) * d),
                              toEye);
#else
  vec3 ambient, lit;
  shadeSample(c, 1.0, directionOfWord(word), toEye, ambient, lit);
  float shadow = 1.0;
#if VXL_SHADOWS
#if VXL_SHADOW_CACHE
  shadow = centreShadow(voxel);  // shadow_cache.glsl
#else
  shadow = shadowTransmittance(indexToWorld(o + 0.5 * (ta + tz) * d));
#endif
#endif
  color += transmittance * a * (ambient + shadow * lit);
#endif
  transmittance *= 1.0 - a;
}

#if VXL_EFFECTS
// The ray-traced mode: true when the ray stops for this pass on entering walk w's current brick
// (continueNextPass stores it to go on in the next); it then carries no background share. w.t is
// a brick's (and so a voxel's) entry: the next pass starts a thousandth of a voxel further,
// inside that voxel, so the voxel before is not met twice.
bool stopsForNextPass(BrickWalk w, vec3 o, vec3 d, vec3 toEye, inout float transmittance) {
  if (!continueNextPass(w.step, o + (w.t + 1e-3 * uUnit) * d, toEye, transmittance)) return false;
  transmittance = 0.0;
  return true;
}
#endif

#if VXL_SCENE
#include "voxlink_scene_trace.glsl"
#else
void traceVoxels(vec3 o, vec3 d, float t0, float t1, vec3 toEye, inout vec3 color,
                 inout float transmittance) {
  for (BrickWalk w = brickWalkBegin(o, d, t0, t1); brickWalkGoesOn(w);) {
#if VXL_EFFECTS
    if (stopsForNextPass(w, o, d, toEye, transmittance)) return;
#endif
    RowWalk walk;
    if (brickWalkEnter(w, o, d, true, walk)) {
      uint voxel;
      float ta, tz;
      while (rowWalkNext(walk, voxel, ta, tz)) {
        uint word = voxelWord(voxel);  // value (8-bit files) and direction in one fetch
        vec4 c = classify(storedBitsOf(voxel, word));
        float a = correctedAlpha(c.a, tz - ta);
        if (a > 0.0) {
          compositeVolumeSample(voxel, word, c.rgb, a, o, d, ta, tz, toEye, color, transmittance);
          if (transmittance <= uStopTransmittance) return;
        }
      }
    }
    if (!brickWalkLeave(w)) break;
  }
}
#endif
