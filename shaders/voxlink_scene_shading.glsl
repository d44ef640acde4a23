// SPDX-License-Identifier: BSD-3-Clause
// Shading and compositing of the geometry hits of voxlink_scene.glsl; included after
// voxlink_shadow.glsl. Mirrors render/effects_tracer.cpp (with every effect off) over
// render/voxel_scene_walker.cpp.
#if VXL_SCENE

// Surface hits cast their shadow rays from this many voxels off the surface along the normal:
// a voxelized surface is one to two voxels thick, and a ray started inside it would shadow
// the surface itself. kSurfaceShadowBias in render/render_model.h.
// A plane or triangle hit lies on the stored surface: 0.3 voxel clears the neighbouring voxels'
// planes yet stays inside the voxel; a triangle needs a rounding margin only
// (kListSurfaceOffset, kTriangleSurfaceOffset in render/render_model.h).
#if VXL_SURFACE_MODE == 0
const float kSurfaceShadowBias = 2.0;
#elif VXL_SURFACE_MODE == 1
const float kSurfaceShadowBias = 0.3;  // kListSurfaceOffset
#else
const float kSurfaceShadowBias = 0.01;  // kTriangleSurfaceOffset
#endif

// Phong terms of a surface hit with unit normal n facing the eye; mirrors shadeSurface() in
// render/render_model.h. Ambient and diffuse weights are the frame's, the highlight the
// material's.
void shadeSurfaceToward(Material m, vec3 n, vec3 toEye, vec3 toLight, out vec3 ambient,
                        out vec3 lit) {
  if (!uShadingEnabled) {
    ambient = m.color;
    lit = vec3(0.0);
    return;
  }
  float ndl = dot(n, toLight);
  float diffuse = max(ndl, 0.0);
  float specular = 0.0;
  if (ndl > 0.0 && m.specular > 0.0) {
    vec3 r = 2.0 * ndl * n - toLight;
    specular = m.specular * pow(max(dot(r, toEye), 0.0), max(m.shininess, 1.0));
  }
  ambient = m.color * uPhong.x;
  lit = m.color * (uPhong.y * diffuse) + vec3(specular);
}

#if VXL_EFFECTS
// Ray-traced mode: shading over the scene's lights, shadow rays and spawned rays; defined in
// voxlink_effects.glsl, included after this file.
void effectsSurface(Material m, vec3 n, vec3 p, vec3 toEye, inout vec3 color,
                    inout float transmittance);
void compositeSurface(Material m, vec3 n, vec3 p, vec3 toEye, inout vec3 color,
                      inout float transmittance) {
  effectsSurface(m, n, p, toEye, color, transmittance);
}
#else
// Composites one surface hit at index-space point p with world normal n.
void compositeSurface(Material m, vec3 n, vec3 p, vec3 toEye, inout vec3 color, inout float transmittance) {
  n = dot(n, toEye) < 0.0 ? -n : n;  // fragments are two-sided
  vec3 ambient, lit;
  shadeSurfaceToward(m, n, toEye, uToLight, ambient, lit);
  float shadow = 1.0;
#if VXL_SHADOWS
  if (uShadingEnabled && dot(n, uToLight) > 0.0)
    shadow = shadowTransmittance(indexToWorld(p) + n * (kSurfaceShadowBias * uUnit));
#endif
  color += transmittance * m.opacity * (ambient + shadow * lit + m.emission);
  transmittance *= 1.0 - m.opacity;
}
#endif

// What one voxel the primary ray crosses over [ta, tz) holds to composite: its surface hit and
// its nearest sphere hit, nearest first, then its volume sample. Found apart from compositing,
// so that voxlink_scene_trace.glsl can composite them outside the row walk where shading is
// costly (shadow walks, the ray-traced mode's lights and spawned rays).
struct VoxelHits {
  int geometry;         // surface and sphere hits, 0 to 2
  vec3 p0, n0, p1, n1;  // their index-space points and world normals, nearest first
  uint m0, m1;          // their materials
  bool volume;          // a volume sample with opacity > 0 follows them
  uint slot;            // its VALU/GRAD slot, voxel word and classified colour
  uint word;
  vec4 c;
  float a;  // its opacity over the chord
  float ta, tz;
};

// The hits of `voxel` over [ta, tz); false when it holds none.
bool voxelHits(uint voxel, vec3 o, vec3 d, float ta, float tz, out VoxelHits h) {
  float tSurface;
  vec3 n;
  uint material;
  bool surface = surfaceHit(voxel, o, d, ta, tz, tSurface, n, material);
  h.geometry = surface ? 1 : 0;
  h.p0 = o + tSurface * d;
  h.n0 = n;
  h.m0 = material;
#if VXL_SPHERES
  float tHit;
  uint sphere;
  vec3 centre;
  bool hitSphere = firstSphereHit(voxel, o, d, ta, tz, tHit, sphere, centre);
  vec3 ps = o + tHit * d;
  // (sphere and centre are unset on a miss)
  vec3 ns = normalize(ps - (hitSphere ? centre : vec3(0.0)));
  uint ms = sphereMaterial(hitSphere ? sphere : 0u);
  bool sphereFirst = hitSphere && !(surface && tSurface <= tHit);
  // The sphere first (then the surface, if any) or after the surface.
  h.p1 = sphereFirst ? h.p0 : ps;
  h.n1 = sphereFirst ? h.n0 : ns;
  h.m1 = sphereFirst ? h.m0 : ms;
  h.p0 = sphereFirst ? ps : h.p0;
  h.n0 = sphereFirst ? ns : h.n0;
  h.m0 = sphereFirst ? ms : h.m0;
  h.geometry += hitSphere ? 1 : 0;
#endif
  h.word = 0u;
  h.c = vec4(0.0);
  h.a = 0.0;
  h.volume = volumeSlot(voxel, h.slot);  // VALU and GRAD of a scene hold the volume voxels only
  if (h.volume) {
    h.word = voxelWord(h.slot);  // value (8-bit files) and direction in one fetch
    h.c = classify(storedBitsOf(h.slot, h.word));
    h.a = correctedAlpha(h.c.a, tz - ta);
    h.volume = h.a > 0.0;
  }
  h.ta = ta;
  h.tz = tz;
  return h.geometry > 0 || h.volume;
}

// Composites the geometry hits of h in order, each after the first only while the ray goes on
// (the first is composited while it does: the walk stops the ray as soon as it ends); the
// caller then composites its volume sample.
void compositeGeometryHits(VoxelHits h, vec3 toEye, inout vec3 color, inout float transmittance) {
#if VXL_EFFECTS || VXL_SHADOWS
  // One call site for both: a hit's shading holds shadow walks (and the ray-traced mode's loop
  // over the lights), which llvmpipe would run for every call site a pass reaches.
  for (int j = 0; j < h.geometry; ++j) {
    if (transmittance > uStopTransmittance)
      compositeSurface(fetchMaterial(j == 0 ? h.m0 : h.m1), j == 0 ? h.n0 : h.n1,
                       j == 0 ? h.p0 : h.p1, toEye, color, transmittance);
  }
#else
  if (h.geometry > 0)
    compositeSurface(fetchMaterial(h.m0), h.n0, h.p0, toEye, color, transmittance);
  if (h.geometry > 1 && transmittance > uStopTransmittance)
    compositeSurface(fetchMaterial(h.m1), h.n1, h.p1, toEye, color, transmittance);
#endif
}

#endif  // VXL_SCENE
