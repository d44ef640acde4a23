// SPDX-License-Identifier: BSD-3-Clause
// The ray-traced scene mode (paper, section 5.2): lights, shadow rays towards each of them, and
// at every surface hit the reflected and refracted rays spawned into the ray buffer with their
// share of the ray's weight (opacity transport). Included when VXL_EFFECTS is 1, after
// voxlink_scene_shading.glsl. Mirrors render/effects_tracer.cpp and light_transport.h.
#if VXL_EFFECTS

uniform bool uReflect;
uniform int uMaxBounces;
uniform float uMinWeight;      // spawned rays lighter than this are dropped
uniform float uSurfaceOffset;  // world: secondary rays start this far off a surface
uniform int uLightCount;
uniform vec4 uLightPosition[VXL_MAX_LIGHTS];  // xyz world; w = 1 directional (xyz towards it)
uniform vec3 uLightRadiance[VXL_MAX_LIGHTS];

// One ray of the ray buffer: 32 bytes (render/gl/detail/effects_buffers.h, GpuRay).
struct GpuRay {
  vec4 originWeight;  // world origin, weight (share of the pixel)
  vec3 direction;     // world, unit
  uint pixelDepth;    // pixel index (y * width + x) | medium << 26 | generation << 28
};

// Where a ray is with respect to refracting objects (light_transport.h, Medium): unknown until
// its first refraction, when the surface normal decides.
const uint kMediumUnknown = 0u, kMediumOutside = 1u, kMediumInside = 2u;
layout(std430, binding = VXL_RAYS_OUT_BINDING) writeonly buffer RaysOut { GpuRay raysOut[]; };
layout(binding = 0, offset = 0) uniform atomic_uint uSpawned;  // rays written to raysOut
layout(binding = 0, offset = 4) uniform atomic_uint uDropped;  // rays the buffer had no room for
uniform uint uRayCapacity;

// The ray being traced.
float gRayWeight;
uint gRayPixel;
int gRayDepth;
uint gRayMedium;

uniform int uStepsPerPass;  // occupied bricks a ray crosses in one pass (paper: n steps)

void storeRay(vec3 origin, vec3 direction, float w, int depth, uint medium) {
  uint i = atomicCounterIncrement(uSpawned);
  if (i >= uRayCapacity) {
    atomicCounterIncrement(uDropped);
    return;
  }
  raysOut[i] = GpuRay(vec4(origin, w), direction, gRayPixel | (medium << 26u) | (uint(depth) << 28u));
}

// A reflected or refracted ray carrying `share` of the current ray.
void spawnRay(vec3 origin, vec3 direction, float share, uint medium) {
  float w = gRayWeight * share;
  if (gRayDepth >= uMaxBounces || !(w > uMinWeight)) return;
  storeRay(origin, direction, w, gRayDepth + 1, medium);
}

// After uStepsPerPass occupied bricks the ray stops for this pass and is stored to go on from
// index-space point p in the next one, with the weight it has left (paper, 5.2.2: a ray is
// iterated a fixed number of steps per pass, so that lanes do not wait for the longest ray).
// Returns true when it was stored; the caller then ends the ray with no background share.
bool continueNextPass(int step, vec3 p, vec3 toEye, float transmittance) {
  if (step < uStepsPerPass) return false;
  storeRay(indexToWorld(p), -toEye, gRayWeight * transmittance, gRayDepth, gRayMedium);
  return true;
}

// Unit direction and distance from world point p to light i.
void lightFrom(int i, vec3 p, out vec3 toLight, out float distance) {
  vec4 l = uLightPosition[i];
  if (l.w > 0.5) {
    toLight = l.xyz;
    distance = kBig;
    return;
  }
  vec3 v = l.xyz - p;
  distance = length(v);
  toLight = distance > 0.0 ? v / distance : vec3(0.0);
}

// Ambient plus each light's lit terms times its shadow ray's transmittance, for a volume sample
// (colour c, unit gradient direction g) at world point p.
vec3 effectsVolumeShade(vec3 c, vec3 g, vec3 p, vec3 toEye) {
  vec3 sum = vec3(0.0);
  for (int i = 0; i < uLightCount; ++i) {
    vec3 toLight;
    float distance;
    lightFrom(i, p, toLight, distance);
    vec3 ambient, lit;
    shadeSampleToward(c, 1.0, g, toEye, toLight, ambient, lit);
    if (i == 0) sum += ambient;
    float shadow = 1.0;
#if VXL_SHADOWS
    shadow = shadowAlong(p, toLight, distance);
#endif
    sum += shadow * lit * uLightRadiance[i];
  }
  return sum;
}

#if VXL_SCENE
// The same for a surface with faced unit normal n at world point p; its shadow rays start
// uSurfaceOffset off it along n.
vec3 effectsSurfaceShade(Material m, vec3 n, vec3 p, vec3 toEye) {
  vec3 sum = vec3(0.0);
  for (int i = 0; i < uLightCount; ++i) {
    vec3 toLight;
    float distance;
    lightFrom(i, p, toLight, distance);
    vec3 ambient, lit;
    shadeSurfaceToward(m, n, toEye, toLight, ambient, lit);
    if (i == 0) sum += ambient;
    float shadow = 1.0;
#if VXL_SHADOWS
    if (uShadingEnabled && dot(n, toLight) > 0.0) {
      vec3 from = p + n * uSurfaceOffset;
      vec3 unused;
      float fromDistance;
      lightFrom(i, from, unused, fromDistance);
      shadow = shadowAlong(from, toLight, fromDistance);
    }
#endif
    sum += shadow * lit * uLightRadiance[i];
  }
  return sum;
}

// A surface hit at index-space point p with stored unit normal n (world): local shading of its
// share, the reflected and refracted rays spawned, the rest passing straight on.
void effectsSurface(Material m, vec3 n, vec3 p, vec3 toEye, inout vec3 color,
                    inout float transmittance) {
  vec3 d = -toEye;
  vec3 nf = dot(n, toEye) < 0.0 ? -n : n;  // faces the eye
  float r = uReflect ? m.reflectivity : 0.0;
  float t = uRefract ? m.transmission : 0.0;
  float local = m.opacity * (1.0 - r - t);
  float reflectShare = m.opacity * r, refractShare = m.opacity * t;
  vec3 refracted = vec3(0.0);
  bool entering = gRayMedium == kMediumUnknown ? dot(d, n) < 0.0 : gRayMedium == kMediumOutside;
  if (refractShare > 0.0) {
    float eta = entering ? 1.0 / m.ior : m.ior;
    float cosI = dot(toEye, nf);
    float k = 1.0 - eta * eta * (1.0 - cosI * cosI);
    if (k < 0.0) {  // total internal reflection
      reflectShare += refractShare;
      refractShare = 0.0;
    } else {
      refracted = normalize(eta * d + (eta * cosI - sqrt(k)) * nf);
    }
  }
  vec3 world = indexToWorld(p);
  vec3 c = m.emission * m.opacity;
  if (local > 0.0) c += local * effectsSurfaceShade(m, nf, world, toEye);
  color += transmittance * c;
  if (reflectShare > 0.0)
    spawnRay(world + nf * uSurfaceOffset, d - 2.0 * dot(d, nf) * nf, transmittance * reflectShare,
             gRayMedium);
  if (refractShare > 0.0)
    spawnRay(world - nf * uSurfaceOffset, refracted, transmittance * refractShare,
             entering ? kMediumInside : kMediumOutside);
  transmittance *= 1.0 - m.opacity;
}
#endif  // VXL_SCENE

#endif  // VXL_EFFECTS
