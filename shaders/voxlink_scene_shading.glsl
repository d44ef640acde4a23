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

// The surface hit and the nearest sphere hit, nearest first, of one voxel the primary ray
// crosses over [ta, tz). The caller composites the voxel's volume sample afterwards, if it has one.
void compositeGeometry(uint voxel, vec3 o, vec3 d, float ta, float tz, vec3 toEye, inout vec3 color,
                       inout float transmittance) {
  float tSurface;
  vec3 n;
  uint material;
  bool surface = surfaceHit(voxel, o, d, ta, tz, tSurface, n, material);
#if VXL_SPHERES
  float tHit;
  uint sphere;
  vec3 centre;
  bool sphereFirst = firstSphereHit(voxel, o, d, ta, tz, tHit, sphere, centre) &&
                     !(surface && tSurface <= tHit);
  if (sphereFirst) {
    vec3 p = o + tHit * d;
    compositeSurface(fetchMaterial(sphereMaterial(sphere)), normalize(p - centre), p, toEye, color,
                     transmittance);
  }
#endif
  if (surface && transmittance > uStopTransmittance)
    compositeSurface(fetchMaterial(material), n, o + tSurface * d, toEye, color, transmittance);
#if VXL_SPHERES
  if (!sphereFirst && tHit < kBig && transmittance > uStopTransmittance) {
    vec3 p = o + tHit * d;
    compositeSurface(fetchMaterial(sphereMaterial(sphere)), normalize(p - centre), p, toEye, color,
                     transmittance);
  }
#endif
}

#endif  // VXL_SCENE
