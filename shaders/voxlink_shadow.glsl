// SPDX-License-Identifier: BSD-3-Clause
// Shadow rays through a VoxLink file: transmittance towards the light with voxel (nearest)
// sampling, skipping empty bricks and walking rows (voxlink_brick_walk.glsl). Mirrors
// ReferenceRenderer::shadowTransmittance.

#include "voxlink_brick_walk.glsl"

// Transmittance from worldPoint towards unit direction toLight, over at most `distance` (world;
// kBig for a directional light). The ray starts one voxel (uUnit) along its way, or
// the surface offset of fragment lists (VoxelSceneWalker::shadowStartOffset).
#if VXL_SURFACE_MODE == 0
const float kShadowStartVoxels = 1.0;
#elif VXL_SURFACE_MODE == 1
const float kShadowStartVoxels = 0.3;
#else
const float kShadowStartVoxels = 0.01;
#endif
float shadowAlong(vec3 worldPoint, vec3 toLight, float distance) {
  float start = kShadowStartVoxels * uUnit;
  vec3 o = worldToIndex(worldPoint + toLight * start);
  vec3 d = directionToIndex(toLight);
  vec2 range = intersectBox(o, d, vec3(uDims));
  float t0 = max(range.x, 0.0), t1 = min(range.y, distance - start);
  float transmittance = 1.0;
  if (!(t0 < t1)) return transmittance;
#if defined(VXL_DYNAMIC_LAYER) && VXL_SCENE
  // The moving meshes and spheres (voxlink_dynamic.glsl): each surface on the way to the light
  // lets its material's share through, as the primary ray composites each.
  transmittance = dynamicTransmittance(o, d, t0, t1);
  if (transmittance < uShadowStop) return transmittance;
#endif
  for (BrickWalk w = brickWalkBegin(o, d, t0, t1); brickWalkGoesOn(w);) {
    RowWalk walk;
    if (brickWalkEnter(w, o, d, false, walk)) {
      uint voxel;
      float ta, tz;
      while (rowWalkNext(walk, voxel, ta, tz)) {
#if VXL_SCENE
        transmittance *= geometryTransmittance(voxel, o, d, ta, tz);
        uint slot;
        if (!volumeSlot(voxel, slot)) continue;
        voxel = slot;  // VALU and GRAD of a scene hold the volume voxels only
#endif
        transmittance *= 1.0 - correctedAlpha(classify(storedBits(voxel)).a, tz - ta);
        if (transmittance < uShadowStop) return transmittance;
      }
    }
    if (!brickWalkLeave(w)) break;
  }
  return transmittance;
}

// Towards the frame's directional light.
float shadowTransmittance(vec3 worldPoint) { return shadowAlong(worldPoint, uToLight, kBig); }
