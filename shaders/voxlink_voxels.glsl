// Voxel (nearest) sampling of a VoxLink file (paper, section 3.1.4): a walk over bricks skips
// unoccupied ones; inside an occupied brick the row walk (voxlink_row_walk.glsl) visits the
// stored voxels along the lists. Each stored voxel contributes over the exact chord the ray
// spends in it. Mirrors ReferenceRenderer::traceVoxels.

void traceVoxels(vec3 o, vec3 d, float t0, float t1, vec3 toEye, inout vec3 color,
                 inout float transmittance) {
  Dda bricks = ddaInit(o / float(VXL_N), d / float(VXL_N), t0, ivec3(0), uBrickGrid - 1);
  float t = t0;
  int limit = uBrickGrid.x + uBrickGrid.y + uBrickGrid.z + 3;
  for (int i = 0; i < limit && t < t1; ++i) {
#if VXL_EFFECTS
    // t is a brick's (and so a voxel's) entry: the next pass starts a thousandth of a voxel
    // further, inside that voxel, so the voxel before is not met twice.
    if (continueNextPass(i, o + (t + 1e-3 * uUnit) * d, toEye, transmittance)) {
      transmittance = 0.0;
      return;
    }
#endif
    int axis = minAxis(bricks.tMax);
    // Runs of empty bricks are crossed here, one occupancy bit each: llvmpipe executes the
    // whole body of this loop for all 8 lanes of a SIMD vector whenever one of them needs it,
    // so an empty brick taking a pass of its own costs as much as an occupied one.
    int k = occupiedIndex(bricks.cell);
    bool outside = false;  // (a return from inside this loop gave wrong images on Mesa 22.3 llvmpipe)
    for (int j = 0; j < limit && k < 0; ++j) {
      t = min(max(bricks.tMax[axis], t), t1);
      ddaAdvance(bricks, axis);
      if (t >= t1 || bricks.cell[axis] < 0 || bricks.cell[axis] >= uBrickGrid[axis]) {
        outside = true;
        break;
      }
      axis = minAxis(bricks.tMax);
      k = occupiedIndex(bricks.cell);
    }
    if (outside) break;
    float tb = min(max(bricks.tMax[axis], t), t1);
    float tIn = t, tOut = tb;
    ivec3 lo, hi;
    uint base;
    if (k >= 0 && tb > t && clipToBrickBounds(o, d, uint(k), bricks.cell, tIn, tOut, lo, hi, base)) {
      RowWalk walk = rowWalkBegin(o, d, tIn, tOut, bricks.cell, uint(k), base, lo, hi);
      uint voxel;
      float ta, tz;
      while (rowWalkNext(walk, voxel, ta, tz)) {
#if VXL_SCENE
        compositeGeometry(voxel, o, d, ta, tz, toEye, color, transmittance);
        if (transmittance <= uStopTransmittance) return;
        uint slot;
        if (!volumeSlot(voxel, slot)) continue;
        voxel = slot;  // VALU and GRAD of a scene hold the volume voxels only
#endif
        vec4 c = classify(storedBits(voxel));
        float a = correctedAlpha(c.a, tz - ta);
        if (a > 0.0) {
#if VXL_EFFECTS
          color += transmittance * a *
                   effectsVolumeShade(c.rgb, decodeGradient(gradientCode(voxel)),
                                      indexToWorld(o + 0.5 * (ta + tz) * d), toEye);
#else
          vec3 ambient, lit;
          shadeSample(c.rgb, 1.0, decodeGradient(gradientCode(voxel)), toEye, ambient, lit);
          float shadow = 1.0;
#if VXL_SHADOWS
          shadow = shadowTransmittance(indexToWorld(o + 0.5 * (ta + tz) * d));
#endif
          color += transmittance * a * (ambient + shadow * lit);
#endif
          transmittance *= 1.0 - a;
          if (transmittance <= uStopTransmittance) return;
        }
      }
    }
    t = tb;
    ddaAdvance(bricks, axis);
    if (bricks.cell[axis] < 0 || bricks.cell[axis] >= uBrickGrid[axis]) break;
  }
}
