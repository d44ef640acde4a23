// SPDX-License-Identifier: BSD-3-Clause
// Primary rays, built exactly as viewer::Camera::primaryRay() builds them, and the move into
// index space, where voxel i spans [i, i+1) and t stays a world distance.

uniform vec3 uEyeWorld;
uniform vec3 uCamForward;  // -back
uniform vec3 uCamRight;    // right * half width of the image plane at distance 1
uniform vec3 uCamUp;       // up * half height
uniform uvec2 uImageSize;

uniform vec3 uVolumeOrigin;   // world centre of voxel (0,0,0)
uniform vec3 uVolumeSpacing;
uniform ivec3 uDims;

vec3 primaryDirection(uvec2 pixel) {
  float sx = 2.0 * (float(pixel.x) + 0.5) / float(uImageSize.x) - 1.0;
  float sy = 1.0 - 2.0 * (float(pixel.y) + 0.5) / float(uImageSize.y);
  return normalize(uCamForward + sx * uCamRight + sy * uCamUp);
}

vec3 worldToIndex(vec3 world) { return (world - uVolumeOrigin) / uVolumeSpacing + 0.5; }
vec3 indexToWorld(vec3 index) { return uVolumeOrigin + (index - 0.5) * uVolumeSpacing; }
vec3 directionToIndex(vec3 dir) { return dir / uVolumeSpacing; }

// [t0, t1] of the ray o + t d inside [0, size] (index space); t0 > t1 when it misses.
vec2 intersectBox(vec3 o, vec3 d, vec3 size) {
  float t0 = -kBig, t1 = kBig;
  for (int a = 0; a < 3; ++a) {
    if (abs(d[a]) < kParallelEpsilon) {
      if (o[a] < 0.0 || o[a] > size[a]) return vec2(1.0, 0.0);
      continue;
    }
    float ta = (0.0 - o[a]) / d[a];
    float tb = (size[a] - o[a]) / d[a];
    t0 = max(t0, min(ta, tb));
    t1 = min(t1, max(ta, tb));
  }
  return vec2(t0, t1);
}
