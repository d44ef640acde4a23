// Shadow rays through a VoxLink file: transmittance towards the light with voxel (nearest)
// sampling, skipping empty bricks and walking rows. Mirrors ReferenceRenderer::shadowTransmittance.

// Transmittance from worldPoint towards unit direction toLight, over at most `distance` (world;
// kBig for a directional light). The ray starts one voxel (uUnit) along its way.
float shadowAlong(vec3 worldPoint, vec3 toLight, float distance) {
  vec3 o = worldToIndex(worldPoint + toLight * uUnit);
  vec3 d = directionToIndex(toLight);
  vec2 range = intersectBox(o, d, vec3(uDims));
  float t0 = max(range.x, 0.0), t1 = min(range.y, distance - uUnit);
  float transmittance = 1.0;
  if (!(t0 < t1)) return transmittance;
  Dda bricks = ddaInit(o / float(VXL_N), d / float(VXL_N), t0, ivec3(0), uBrickGrid - 1);
  float t = t0;
  int limit = uBrickGrid.x + uBrickGrid.y + uBrickGrid.z + 3;
  for (int i = 0; i < limit && t < t1; ++i) {
    int axis = minAxis(bricks.tMax);
    float tb = min(max(bricks.tMax[axis], t), t1);
    int k = occupiedIndex(bricks.cell);
    float tIn = t, tOut = tb;
    ivec3 lo, hi;
    uint base;
    if (k >= 0 && tb > t && clipToBrickBounds(o, d, uint(k), bricks.cell, tIn, tOut, lo, hi, base)) {
      RowWalk walk = rowWalkBegin(o, d, tIn, tOut, bricks.cell, uint(k), base, lo, hi);
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
    t = tb;
    ddaAdvance(bricks, axis);
    if (bricks.cell[axis] < 0 || bricks.cell[axis] >= uBrickGrid[axis]) break;
  }
  return transmittance;
}

// Towards the frame's directional light.
float shadowTransmittance(vec3 worldPoint) { return shadowAlong(worldPoint, uToLight, kBig); }
