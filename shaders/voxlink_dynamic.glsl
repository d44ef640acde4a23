// SPDX-License-Identifier: BSD-3-Clause
// The dynamic layer of a dynamic scene (render/gl/gl_dynamic_layer.h): moving meshes voxelized
// this frame on the GPU into a brick map over the grid and a pool of bricks (per voxel the sum
// of area x unit normal in fixed point and material + 1). The ray tracer takes the layer's
// occupied voxels along the ray (a hit at each one's entry, as the static mean-mode fragments)
// nearest first and composites them between the static file's stretches
// (voxlink_dynamic_trace.glsl). Defined when VXL_DYNAMIC_LAYER is; VXL_DYN_N is the layer's
// brick edge. With VXL_DYN_SPHERES the moving spheres too (render/gl/gl_dynamic_spheres.h): per
// brick of VXL_DYN_SPHERE_N voxels a list of spheres, intersected exactly; dynamicSurfaceNext()
// gives the surfaces of both nearest first. VXL_DYN_POOLS: the pool's storage buffers, slot s in
// buffer s / VXL_DYN_POOL_SLOTS (shaders/dynamic_layer.glsl).
#ifdef VXL_DYNAMIC_LAYER

layout(std430, binding = 59) readonly buffer DynBrickMap { uint dynBrickMap[]; };
layout(std430, binding = 60) readonly buffer DynPool { ivec4 dynPool[]; };
#if VXL_DYN_POOLS > 1
layout(std430, binding = 50) readonly buffer DynPool1 { ivec4 dynPool1[]; };
#endif
#if VXL_DYN_POOLS > 2
layout(std430, binding = 51) readonly buffer DynPool2 { ivec4 dynPool2[]; };
#endif
#if VXL_DYN_POOLS > 3
layout(std430, binding = 52) readonly buffer DynPool3 { ivec4 dynPool3[]; };
#endif
uniform ivec3 uDynLo, uDynHi;  // voxel box [lo, hi) of this frame's moving triangles
uniform ivec3 uDynBrickGrid;   // bricks per axis of the layer's map

// Voxel v of the brick in pool slot `slot`.
ivec4 dynPoolVoxel(uint slot, uint v) {
  const uint n3 = uint(VXL_DYN_N * VXL_DYN_N * VXL_DYN_N);
#if VXL_DYN_POOLS > 1
  uint part = slot / uint(VXL_DYN_POOL_SLOTS);
  uint e = (slot - part * uint(VXL_DYN_POOL_SLOTS)) * n3 + v;
#if VXL_DYN_POOLS > 3
  if (part == 3u) return dynPool3[e];
#endif
#if VXL_DYN_POOLS > 2
  if (part == 2u) return dynPool2[e];
#endif
  if (part == 1u) return dynPool1[e];
  return dynPool[e];
#else
  return dynPool[slot * n3 + v];
#endif
}

// The bricks of n voxels that the voxel box [lo, hi) spans, walked along o + t d from where the
// ray enters the box in [t0, t1) to tb; false when it misses the box there. `limit` bounds the
// walk's steps (the bricks' span along each axis, plus 3).
bool dynamicBrickWalk(vec3 o, vec3 d, float t0, float t1, ivec3 lo, ivec3 hi, int n,
                      out float ta, out float tb, out Dda bricks, out int limit) {
  if (any(greaterThanEqual(lo, hi))) return false;
  vec2 range = intersectBox(o - vec3(lo), d, vec3(hi - lo));
  ta = max(range.x, t0);
  tb = min(range.y, t1);
  if (!(ta < tb)) return false;
  ivec3 bLo = lo / n, bHi = (hi - 1) / n;
  bricks = ddaInit(o / float(n), d / float(n), ta, bLo, bHi);
  limit = (bHi.x - bLo.x) + (bHi.y - bLo.y) + (bHi.z - bLo.z) + 3;
  return true;
}

// First voxel of the layer on o + t d (index space) in [t0, t1): its entry tHit, world normal n
// (unit; towards the ray where the sides cancel), material and cell.
bool dynamicMeshHit(vec3 o, vec3 d, float t0, float t1, out float tHit, out vec3 n,
                    out uint material, out ivec3 cell) {
  tHit = kBig;
  const int bn = VXL_DYN_N;
  float ta, tb;
  Dda bricks;
  int limit;
  if (!dynamicBrickWalk(o, d, t0, t1, uDynLo, uDynHi, bn, ta, tb, bricks, limit)) return false;
  float t = ta;
  for (int i = 0; i < limit && t < tb; ++i) {
    int axis = minAxis(bricks.tMax);
    float tOut = min(max(bricks.tMax[axis], t), tb);
    ivec3 c = bricks.cell;
    uint slot = dynBrickMap[(c.z * uDynBrickGrid.y + c.y) * uDynBrickGrid.x + c.x];
    if (slot < 0xfffffffeu && tOut > t) {  // not empty, nor claimed without a pool slot
      Dda voxels = ddaInit(o, d, t, c * bn, c * bn + (bn - 1));
      float tv = t;
      for (int j = 0; j < 3 * bn + 3 && tv < tOut; ++j) {
        int va = minAxis(voxels.tMax);
        ivec3 l = voxels.cell - c * bn;
        // The voxel walk's exit times round differently from the brick walk's: a step past the
        // brick's face before tOut would read another voxel of the pool (another brick's).
        if (any(lessThan(l, ivec3(0))) || any(greaterThanEqual(l, ivec3(bn)))) break;
        ivec4 e = dynPoolVoxel(slot, uint((l.z * bn + l.y) * bn + l.x));
        if (e.w != 0) {
          tHit = tv;
          cell = voxels.cell;
          vec3 sum = vec3(e.xyz);
          n = dot(sum, sum) > 0.0 ? normalize(sum) : -normalize(d);
          material = uint(e.w - 1);
          return true;
        }
        tv = min(max(voxels.tMax[va], tv), tOut);
        ddaAdvance(voxels, va);
      }
    }
    t = tOut;
    ddaAdvance(bricks, axis);
  }
  return false;
}

#ifdef VXL_DYN_SPHERES
layout(std430, binding = 53) readonly buffer DynSphereHeads { uint dynSphereHeads[]; };
layout(std430, binding = 54) readonly buffer DynSphereNodes { uvec2 dynSphereNodes[]; };
// 8 words each: centre and radius (float bits, world units), material; words, so that the
// material's bits are never read as a float (a denormal a driver could flush)
layout(std430, binding = 55) readonly buffer DynSpheres { uint dynSpheres[]; };
uniform ivec3 uDynSphereLo, uDynSphereHi;  // voxel box of this frame's moving spheres
uniform ivec3 uDynSphereBrickGrid;

// The nearest moving sphere hit on o + t d in [t0, t1): the bricks of the spheres' box in ray
// order; in each, the nearest hit of its spheres inside the brick's chord (a hit in a later brick
// is that brick's, where the sphere is listed too). Normal and material as the static path's
// spheres (voxlink_scene_shading.glsl: normalize(p - centre)).
bool dynamicSphereHit(vec3 o, vec3 d, float t0, float t1, out float tHit, out vec3 n,
                      out uint material) {
  tHit = kBig;
  const int bn = VXL_DYN_SPHERE_N;
  float ta, tb;
  Dda bricks;
  int limit;
  if (!dynamicBrickWalk(o, d, t0, t1, uDynSphereLo, uDynSphereHi, bn, ta, tb, bricks, limit))
    return false;
  float t = ta;
  for (int i = 0; i < limit && t < tb; ++i) {
    int axis = minAxis(bricks.tMax);
    float tOut = min(max(bricks.tMax[axis], t), tb);
    ivec3 c = bricks.cell;
    uint node = dynSphereHeads[(c.z * uDynSphereBrickGrid.y + c.y) * uDynSphereBrickGrid.x + c.x];
    vec3 centre;
    for (; node != 0xffffffffu; node = dynSphereNodes[node].y) {
      uint s = dynSphereNodes[node].x * 8u;
      uvec3 centreBits = uvec3(dynSpheres[s], dynSpheres[s + 1u], dynSpheres[s + 2u]);
      vec3 cs = worldToIndex(uintBitsToFloat(centreBits));
      float th = sphereHitAt(cs, uintBitsToFloat(dynSpheres[s + 3u]) / uVolumeSpacing.x, o, d,
                             max(t, 0.0));
      if (th >= t && th < tOut && th < tHit) {
        tHit = th;
        centre = cs;
        material = dynSpheres[s + 4u];
      }
    }
    if (tHit < kBig) {
      n = normalize(o + tHit * d - centre);
      return true;
    }
    t = tOut;
    ddaAdvance(bricks, axis);
  }
  return false;
}
#endif

// The moving surfaces along a ray, nearest first, as the static path orders a voxel's
// surfaces (voxlink_scene_shading.glsl, voxelHits): every voxel of the mesh layer the ray
// crosses (a hit at its entry, as a static mean-mode voxel) and, per voxel, the first moving
// sphere hit inside it (as firstSphereHit). A mesh voxel wins a tie, as a static voxel's surface
// does against its spheres. Each kind keeps its own cursor and its next hit, found once: the
// spheres are searched only up to the next mesh voxel, so an opaque mesh costs one walk of each.
struct DynamicSurfaces {
  float t1;
  float meshFrom, sphereFrom;  // where each kind's next search starts
  float meshT, sphereT;        // its next hit; -1: not searched (from there), kBig: none is left
  vec3 meshN, sphereN;
  uint meshMaterial, sphereMaterial;
  ivec3 meshCell;
};

DynamicSurfaces dynamicSurfacesBegin(float t0, float t1) {
  DynamicSurfaces s;
  s.t1 = t1;
  s.meshFrom = s.sphereFrom = t0;
  s.meshT = s.sphereT = -1.0;
  return s;
}

// The next moving surface on o + t d: its t, unit world normal, material, whether it is a mesh
// voxel's, and the ray's chord [x, y) through the voxel it lies in. False when none is left.
bool dynamicSurfaceNext(vec3 o, vec3 d, inout DynamicSurfaces s, out float tHit, out vec3 n,
                        out uint material, out bool isMesh, out vec2 chord) {
  if (s.meshT < 0.0 &&
      !dynamicMeshHit(o, d, s.meshFrom, s.t1, s.meshT, s.meshN, s.meshMaterial, s.meshCell))
    s.meshT = kBig;
#ifdef VXL_DYN_SPHERES
  if (s.sphereT < 0.0) {
    float limit = min(s.meshT, s.t1);
    if (!dynamicSphereHit(o, d, s.sphereFrom, limit, s.sphereT, s.sphereN, s.sphereMaterial)) {
      // None before the mesh voxel: searched from there once that voxel is taken.
      s.sphereT = limit < s.t1 ? -1.0 : kBig;
      s.sphereFrom = max(s.sphereFrom, limit);
    }
  }
  isMesh = !(s.sphereT >= 0.0 && s.sphereT < s.meshT);
#else
  isMesh = true;
#endif
  if (isMesh) {
    if (s.meshT >= kBig) return false;
    tHit = s.meshT;
    n = s.meshN;
    material = s.meshMaterial;
    chord = intersectBox(o - vec3(s.meshCell), d, vec3(1.0));
    // The next voxel: a thousandth of a voxel past this one's exit, so rounding cannot meet it
    // again.
    s.meshFrom = max(chord.y, tHit) + 1e-3 * uUnit;
    s.meshT = -1.0;
    return true;
  }
#ifdef VXL_DYN_SPHERES
  tHit = s.sphereT;
  n = s.sphereN;
  material = s.sphereMaterial;
  chord = intersectBox(o - floor(o + tHit * d), d, vec3(1.0));
  s.sphereFrom = max(chord.y, tHit + 1e-4 * uUnit);  // the next sphere hit in a later voxel
  s.sphereT = -1.0;
#endif
  return true;
}

#if VXL_SCENE
// Transmittance of the moving surfaces between t0 and t1 for a shadow ray: each one the ray
// crosses lets its material's share through, as each static surface does (geometryTransmittance).
float dynamicTransmittance(vec3 o, vec3 d, float t0, float t1) {
  DynamicSurfaces s = dynamicSurfacesBegin(t0, t1);
  float transmittance = 1.0, tHit;
  vec3 n;
  uint material;
  bool isMesh;
  vec2 chord;
  while (transmittance >= uShadowStop &&
         dynamicSurfaceNext(o, d, s, tHit, n, material, isMesh, chord))
    transmittance *= surfaceTransmittance(fetchMaterial(material));
  return transmittance;
}
#endif

#endif
