// SPDX-License-Identifier: BSD-3-Clause
// A ray through a dynamic scene (docs/dynamic-scenes.md): the moving surfaces
// (voxlink_dynamic.glsl, dynamicSurfaceNext) composited nearest first, each between the stretches
// of the static file (traceVoxels) before and after it, so a semi-transparent moving mesh or
// sphere shows every surface it has and what lies behind, as the static scene frozen at that time
// does. The primary frame and the ray-traced mode's rays alike; included after
// voxlink_voxels.glsl.
#ifdef VXL_DYNAMIC_LAYER

// At most this many moving surfaces per ray (a ray along a semi-transparent mesh crosses one per
// voxel); past it the rest of the static file is drawn.
const int kMaxDynamicSurfaces = 1024;

void traceVoxelsAndLayer(vec3 o, vec3 d, float t0, float t1, vec3 toEye, inout vec3 color,
                         inout float transmittance) {
  DynamicSurfaces surfaces = dynamicSurfacesBegin(t0, t1);
  // The static file is drawn up to here: a static voxel is drawn once, whole, in one stretch,
  // except a voxel that holds a moving surface (below).
  float tStatic = t0;
  const float inside = 1e-3 * uUnit;
  float tHit;
  vec3 n;
  uint material;
  bool isMesh;
  vec2 chord;
  // One call of traceVoxels and of compositeSurface per pass of the loop, whether a surface
  // was found or not: rays of one SIMD vector that hit a moving object and rays that miss it
  // walk the static file together (with a call site for each, the opaque animated dragon's
  // render took 1.18x main's on llvmpipe in one A/B run; with one, 0.97-1.03x).
  for (int k = 0; k <= kMaxDynamicSurfaces; ++k) {
    bool found = k < kMaxDynamicSurfaces &&
                 dynamicSurfaceNext(o, d, surfaces, tHit, n, material, isMesh, chord);
    // A mesh voxel's surface lies at its entry, before the static voxel there (a tie: the moving
    // one first), so the stretch ends a thousandth of a voxel before it and the next one starts
    // inside that voxel. A sphere hit lies inside its voxel: the static voxel's part in front of
    // it (its surface, at the entry, included) goes first, and the next stretch starts after it.
    float stretchEnd = !found ? t1 : (isMesh ? chord.x - inside : tHit);
    if (stretchEnd > tStatic) traceVoxels(o, d, tStatic, stretchEnd, toEye, color, transmittance);
    if (!found || transmittance <= uStopTransmittance) return;
    compositeSurface(fetchMaterial(material), n, o + tHit * d, toEye, color, transmittance);
    if (transmittance <= uStopTransmittance) return;
    tStatic = max(tStatic, (isMesh ? chord.x : chord.y) + inside);
  }
}

#endif
