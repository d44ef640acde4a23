// SPDX-License-Identifier: BSD-3-Clause
// Geometry in a VoxLink scene (format version 2; paper, sections 3.1.1-3.1.2): per voxel a
// surface fragment (polar normal + material) or, in version 2.1, a list of planes or triangle
// references, references to implicit spheres intersected exactly, and a bit saying whether the
// voxel also carries a volume sample. Included when
// VXL_SCENE is 1; the sections come through voxlink_sections.glsl (surfWord, vmskWord,
// matlWord and, with VXL_SPHERES, sphrWord, srofWord, sridWord).
// Mirrors render/voxel_scene_walker.cpp; docs/scene.md states the model. Shading of
// hits, which needs shadowTransmittance(), is in voxlink_scene_shading.glsl.
#if VXL_SCENE

const uint kNoSurface = 0xFFFFFFFFu;

struct Material {
  vec3 color;
  float opacity;
  vec3 emission;
  float reflectivity;
  float transmission;
  float ior;
  float specular;
  float shininess;
};

float matlFloat(uint word) { return uintBitsToFloat(matlWord(word)); }

// MaterialRecord (format/layout.h): 16 words per material.
Material fetchMaterial(uint m) {
  uint b = m * 16u;
  Material r;
  r.color = vec3(matlFloat(b), matlFloat(b + 1u), matlFloat(b + 2u));
  r.opacity = matlFloat(b + 3u);
  r.emission = vec3(matlFloat(b + 4u), matlFloat(b + 5u), matlFloat(b + 6u));
  r.reflectivity = matlFloat(b + 7u);
  r.transmission = matlFloat(b + 8u);
  r.ior = matlFloat(b + 9u);
  r.specular = matlFloat(b + 10u);
  r.shininess = matlFloat(b + 11u);
  return r;
}

// Slot of voxel i in a payload indexed by a mask (format/mask_rank.h): set bits before it.
uint maskSlot(uint word, uint rankBefore, uint voxel) {
  uint below = (voxel & 31u) == 0u ? 0u : word << (32u - (voxel & 31u));
  return rankBefore + uint(bitCount(below));
}

// The VALU/GRAD slot of a voxel's volume sample; false when it has none.
bool volumeSlot(uint voxel, out uint slot) {
  uint word = vmskWord(voxel >> 5u);
  slot = maskSlot(word, vmskRank(voxel >> 5u), voxel);
  return ((word >> (voxel & 31u)) & 1u) != 0u;
}

// The voxel's surface fragment word, or kNoSurface.
uint surfaceOf(uint voxel) {
  uint word = smskWord(voxel >> 5u);
  if (((word >> (voxel & 31u)) & 1u) == 0u) return kNoSurface;
  return surfWord(maskSlot(word, smskRank(voxel >> 5u), voxel));
}

// Nearest t >= tMin at which o + t d meets the sphere of `centre` and `radius` (index space),
// or kBig. Also the moving spheres' (voxlink_dynamic.glsl), so both are intersected alike.
float sphereHitAt(vec3 centre, float radius, vec3 o, vec3 d, float tMin) {
  // The discriminant from the ray's closest approach to the centre, r^2 - |perp|^2, instead of
  // b^2 - a c: that difference of two large numbers loses the silhouette in float for rays that
  // start far from the sphere (a tangent ray's hit flipped between float and double).
  vec3 oc = o - centre;
  float a = dot(d, d), along = dot(oc, d) / a;
  vec3 perp = oc - along * d;
  float disc = radius * radius - dot(perp, perp);
  if (disc < 0.0) return kBig;
  float root = sqrt(disc / a);
  float tNear = -along - root, tFar = -along + root;
  return tNear >= tMin ? tNear : (tFar >= tMin ? tFar : kBig);
}

#if VXL_SPHERES
float sphrFloat(uint word) { return uintBitsToFloat(sphrWord(word)); }

// Nearest t >= tMin at which o + t d (index space) meets sphere s, or kBig. The sphere's centre
// and radius are stored in world units; voxels of a scene with spheres are cubic.
float sphereHit(uint s, vec3 o, vec3 d, float tMin, out vec3 centre) {
  uint b = s * 8u;
  centre = worldToIndex(vec3(sphrFloat(b), sphrFloat(b + 1u), sphrFloat(b + 2u)));
  return sphereHitAt(centre, sphrFloat(b + 3u) / uVolumeSpacing.x, o, d, tMin);
}

uint sphereMaterial(uint s) { return sphrWord(s * 8u + 4u); }

// The first sphere hit of this voxel inside its chord [ta, tz), or false.
bool firstSphereHit(uint voxel, vec3 o, vec3 d, float ta, float tz, out float tHit, out uint sphere,
                    out vec3 centre) {
  tHit = kBig;
  uint word = pmskWord(voxel >> 5u);
  if (((word >> (voxel & 31u)) & 1u) == 0u) return false;
  uint s = maskSlot(word, pmskRank(voxel >> 5u), voxel);
  uint end = srofWord(s + 1u);
  for (uint r = srofWord(s); r < end; ++r) {
    uint id = sridWord(r);
    vec3 c;
    float t = sphereHit(id, o, d, max(ta, 0.0), c);
    if (t >= ta && t < tz && t < tHit) {
      tHit = t;
      sphere = id;
      centre = c;
    }
  }
  return tHit < kBig;
}
#endif

// Version 2.1/2.2 fragment lists (VXL_SURFACE_MODE 1 planes, 2 triangles; format/layout.h): the
// sections come as frofWord and fragEntry (uvec2 per FragmentRecord), or tridWord and trisWord
// (10 words per TriangleRecord). Mirrors VoxelSceneWalker::listHit.
#if VXL_SURFACE_MODE == 1
const float kPlaneOffsetUnit = 1.0 / 4096.0;  // format/layout.h
// Plane hits count this far (voxels) outside the chord along the normal, and kExtentTolerance
// outside the extent box, so neighbouring voxels' planes leave no crack (format/fragment_extent.h).
const float kPlaneHitTolerance = 1.0 / 64.0;
const float kPlaneHitReach = 8.0;            // at most 8 tolerances along the ray (edge-on planes)
const float kExtentTolerance = 1.0 / 128.0;  // outside the extent box

// Whether a voxel-local point lies in a fragment's extent box (format/fragment_extent.h; code 0
// is the whole voxel, as in version 2.1 files).
bool extentHolds(uint code, vec3 local) {
  uint axis = code & 3u;
  float u = local[(axis + 1u) % 3u], v = local[(axis + 2u) % 3u];
  float uLo = float((code >> 2u) & 7u) / 8.0, uHi = 1.0 - float((code >> 5u) & 7u) / 8.0;
  float vLo = float((code >> 8u) & 7u) / 8.0, vHi = 1.0 - float((code >> 11u) & 7u) / 8.0;
  // A bound on the voxel's face is no bound (a hit in the chord may round just outside); the
  // others are grown by kExtentTolerance.
  return (uLo == 0.0 || u >= uLo - kExtentTolerance) &&
         (uHi == 1.0 || u <= uHi + kExtentTolerance) &&
         (vLo == 0.0 || v >= vLo - kExtentTolerance) && (vHi == 1.0 || v <= vHi + kExtentTolerance);
}

// A convex fragment's hit (world, from the voxel centre) counts only behind or on the voxel's
// other planes (bit 14; format/fragment_extent.h, kConvexTolerance).
bool behindOthers(uint code, uint slot, uint self, vec3 fromCentre) {
  if ((code & 0x4000u) == 0u) return true;
  uint end = frofWord(slot + 1u);
  for (uint g = frofWord(slot); g < end; ++g) {
    if (g == self) continue;
    uvec2 e = fragEntry(g);
    float offset = float(int(e.y << 16u) >> 16) * (kPlaneOffsetUnit * uUnit);
    if (dot(decodeGradient(e.x & 0xFFFFu), fromCentre) - offset > 1e-4 * uUnit) return false;
  }
  return true;
}
#endif
#if VXL_SURFACE_MODE == 2
vec3 trisVertex(uint b) {
  return vec3(uintBitsToFloat(trisWord(b)), uintBitsToFloat(trisWord(b + 1u)),
              uintBitsToFloat(trisWord(b + 2u)));
}
#endif

// The surface hit of a voxel the ray o + t d (index space) crosses over [ta, tz): with one
// fragment per voxel at the chord's entry; with lists the nearest plane or triangle hit inside
// the chord (none: false). n is the stored unit world normal, not faced.
bool surfaceHit(uint voxel, vec3 o, vec3 d, float ta, float tz, out float tHit, out vec3 n,
                out uint material) {
  tHit = kBig;
#if VXL_SURFACE_MODE == 0
  uint surface = surfaceOf(voxel);
  if (surface == kNoSurface) return false;
  tHit = ta;
  n = decodeGradient(surface & 0xFFFFu);
  material = surface >> 16u;
  return true;
#else
  uint word = smskWord(voxel >> 5u);
  if (((word >> (voxel & 31u)) & 1u) == 0u) return false;
  uint s = maskSlot(word, smskRank(voxel >> 5u), voxel);
  // The ray in world units, with the same parameter t.
  vec3 origin = indexToWorld(o), direction = d * uVolumeSpacing;
#if VXL_SURFACE_MODE == 1
  vec3 cell = floor(o + 0.5 * (ta + tz) * d);
  vec3 centre = indexToWorld(cell + 0.5);
  vec3 fromCentre = origin - centre;
#endif
  uint end = frofWord(s + 1u);
  for (uint f = frofWord(s); f < end; ++f) {
#if VXL_SURFACE_MODE == 1
    uvec2 e = fragEntry(f);
    vec3 fn = decodeGradient(e.x & 0xFFFFu);
    float along = dot(fn, direction);
    if (along == 0.0) continue;
    float offset = float(int(e.y << 16u) >> 16) * (kPlaneOffsetUnit * uUnit);
    float t = (offset - dot(fn, fromCentre)) / along;
    // The chord grown at both ends (not before the ray's start, t = 0), as the float64 walker.
    float grow =
        kPlaneHitTolerance * uUnit * min(1.0 / abs(along), kPlaneHitReach / length(direction));
    if (t >= max(ta - grow, 0.0) && t < tz + grow && t < tHit &&
        extentHolds(e.y >> 16u, o + t * d - cell) &&
        behindOthers(e.y >> 16u, s, f, fromCentre + t * direction)) {
      tHit = t;
      n = fn;
      material = e.x >> 16u;
    }
#else
    uint b = tridWord(f) * 10u;
    vec3 a = trisVertex(b);
    vec3 e1 = trisVertex(b + 3u) - a, e2 = trisVertex(b + 6u) - a;
    vec3 p = cross(direction, e2);
    float det = dot(e1, p);
    if (det == 0.0) continue;
    vec3 fromA = origin - a;
    float u = dot(fromA, p) / det;
    if (u < 0.0 || u > 1.0) continue;
    vec3 q = cross(fromA, e1);
    float v = dot(direction, q) / det;
    if (v < 0.0 || u + v > 1.0) continue;
    float t = dot(e2, q) / det;
    if (t >= ta && t < tz && t < tHit) {
      tHit = t;
      n = normalize(cross(e1, e2));
      material = trisWord(b + 9u);
    }
#endif
  }
  return tHit < kBig;
#endif
}

// Transmittance of a surface for shadow rays: 1 - opacity, and in the ray-traced mode with
// refraction on, the refracted share passes too (light_transport.h, shadowTransmittanceOf).
#if VXL_EFFECTS
uniform bool uRefract;
float surfaceTransmittance(Material m) {
  return 1.0 - m.opacity * (1.0 - (uRefract ? m.transmission : 0.0));
}
#else
float surfaceTransmittance(Material m) { return 1.0 - m.opacity; }
#endif

// Transmittance of the geometry in one voxel a shadow ray crosses over [ta, tz).
float geometryTransmittance(uint voxel, vec3 o, vec3 d, float ta, float tz) {
  float transmittance = 1.0;
  float tSurface;
  vec3 n;
  uint material;
  if (surfaceHit(voxel, o, d, ta, tz, tSurface, n, material))
    transmittance *= surfaceTransmittance(fetchMaterial(material));
#if VXL_SPHERES
  float tHit;
  uint sphere;
  vec3 centre;
  if (firstSphereHit(voxel, o, d, ta, tz, tHit, sphere, centre))
    transmittance *= surfaceTransmittance(fetchMaterial(sphereMaterial(sphere)));
#endif
  return transmittance;
}
#endif  // VXL_SCENE
