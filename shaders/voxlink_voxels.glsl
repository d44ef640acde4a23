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
    int axis = minAxis(bricks.tMax);
    float tb = min(max(bricks.tMax[axis], t), t1);
    int k = occupiedIndex(brickId(bricks.cell));
    float tIn = t, tOut = tb;
    ivec3 lo, hi;
    if (k >= 0 && tb > t && clipToBrickBounds(o, d, uint(k), bricks.cell, tIn, tOut, lo, hi)) {
      RowWalk walk = rowWalkBegin(o, d, tIn, tOut, bricks.cell, uint(k), lo, hi);
      uint voxel;
      float ta, tz;
      while (rowWalkNext(walk, voxel, ta, tz)) {
        vec4 c = classify(storedBits(voxel));
        float a = correctedAlpha(c.a, tz - ta);
        if (a > 0.0) {
          vec3 ambient, lit;
          shadeSample(c.rgb, 1.0, decodeGradient(gradientCode(voxel)), toEye, ambient, lit);
          float shadow = 1.0;
#if VXL_SHADOWS
          shadow = shadowTransmittance(indexToWorld(o + 0.5 * (ta + tz) * d));
#endif
          color += transmittance * a * (ambient + shadow * lit);
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
