// Shadow rays through the dense volume: transmittance towards the light with voxel (nearest)
// sampling over every cell. Mirrors ReferenceRenderer::shadowTransmittance.

uniform usampler3D uDenseValues;     // stored value bits (R8UI, R16UI, R32UI)
uniform usampler3D uDenseGradients;  // polar16 codes (R16UI)

float shadowTransmittance(vec3 worldPoint) {
  vec3 o = worldToIndex(worldPoint + uToLight * uUnit);
  vec3 d = directionToIndex(uToLight);
  vec2 range = intersectBox(o, d, vec3(uDims));
  float t = max(range.x, 0.0), t1 = range.y;
  float transmittance = 1.0;
  if (!(t < t1)) return transmittance;
  Dda voxels = ddaInit(o, d, t, ivec3(0), uDims - 1);
  int limit = uDims.x + uDims.y + uDims.z + 3;
  for (int i = 0; i < limit && t < t1; ++i) {
    int axis = minAxis(voxels.tMax);
    float tn = min(max(voxels.tMax[axis], t), t1);
    uint bits = texelFetch(uDenseValues, voxels.cell, 0).r;
    transmittance *= 1.0 - correctedAlpha(classify(bits).a, tn - t);
    if (transmittance < uShadowStop) return transmittance;
    t = tn;
    ddaAdvance(voxels, axis);
    if (voxels.cell[axis] < 0 || voxels.cell[axis] >= uDims[axis]) break;
  }
  return transmittance;
}

