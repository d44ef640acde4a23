// SPDX-License-Identifier: BSD-3-Clause
// Version 2.2: where a plane fragment's surface piece lies inside its voxel. A plane clipped only
// to its voxel crosses the whole voxel, also where the real surface ends inside it (silhouettes,
// thin parts, creases); the extent is the box of the piece seen along one axis (`axis`, the
// normal's largest component), in eighths of the voxel, rounded outwards. A ray's hit on the
// plane counts only where its two other coordinates lie in that box. Code 0 is the whole voxel,
// so version 2.1 files (the field was reserved, zero) read as before.
//
//   bits 0-1   axis the box is seen along (0 x, 1 y, 2 z; 3 is refused)
//   bits 2-4   lower bound of axis u = (axis + 1) % 3, in eighths from the voxel's low face
//   bits 5-7   upper bound of u, in eighths *below* the voxel's high face
//   bits 8-10  lower bound of v = (axis + 2) % 3
//   bits 11-13 upper bound of v, in eighths below the high face
//   bit 14     convex: the piece meets every other plane of its voxel at a convex crease (a
//              silhouette, a thin part's tip), so a hit counts only behind or on each of them
//              (kConvexTolerance); the planes then end where they cross, as the surface does
//   bit 15     zero
// Each interval keeps lower + upper <= 7 eighths: at least an eighth of the voxel wide.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>

namespace voxlink::format {

inline constexpr uint32_t kExtentSteps = 8;  // the box's bounds are multiples of 1/8 voxel
inline constexpr uint16_t kExtentConvex = 1u << 14;
// How far (in the voxel's smallest spacing) a convex piece's hit may lie in front of another
// plane of its voxel and still count: rounding, not geometry.
inline constexpr double kConvexTolerance = 1e-4;
// How far (in the voxel's smallest spacing) a plane hit may lie outside its voxel's chord, along
// the plane's normal, and still count. Neighbouring voxels' planes do
// not meet exactly: each has its own quantized normal (up to 0.78 degrees off) and passes through
// its own piece's centroid, so at a shared face they part by up to a few thousandths of a voxel,
// and a ray crossing the surface there is in front of one plane and already behind the next
// (docs/surface-modes.md, "Rays through the red wall"). 1/64 voxel closes those cracks.
inline constexpr double kPlaneHitTolerance = 1.0 / 64.0;
// How far (voxel-local) a plane hit may lie outside its extent box: the plane's hit lies off the
// real surface's by the normal's quantization, so a piece ending on an eighth lost hits just
// inside its edge (0.003 voxel on the Cornell box's red wall). Half the chord's tolerance: a
// full 1/64 let planes reach past silhouettes (4 extra pixels on molecule-glass at 512).
inline constexpr double kExtentTolerance = 1.0 / 128.0;
// The chord grows by kPlaneHitTolerance / |cos| along the ray, where cos is between the ray and the
// normal, at most this many tolerances (1/8 voxel): rays within 7.2 degrees of the plane grow no
// further, so planes seen edge-on at silhouettes do not reach out of their voxels.
inline constexpr double kPlaneHitReach = 8.0;

struct FragmentExtent {
  int axis = 0;                    // the box is seen along this axis
  std::array<double, 2> lo{0, 0};  // u, v lower bounds, voxel-local [0, 1]
  std::array<double, 2> hi{1, 1};  // u, v upper bounds
  bool convex = false;             // clipped by the voxel's other planes (bit 14)
};

// The code of the smallest box on the eighths grid holding [lo, hi] (voxel-local; values outside
// [0, 1] are clamped), seen along `axis`.
inline uint16_t encodeExtent(int axis, const std::array<double, 2>& lo,
                             const std::array<double, 2>& hi, bool convex = false) {
  uint16_t code = uint16_t((axis & 3) | (convex ? kExtentConvex : 0));
  for (int k = 0; k < 2; ++k) {
    const double steps = double(kExtentSteps);
    int low = int(std::floor(std::fmin(std::fmax(lo[k], 0.0), 1.0) * steps));
    int high = int(std::floor((1.0 - std::fmin(std::fmax(hi[k], 0.0), 1.0)) * steps));
    low = low > 7 ? 7 : low;
    high = high > 7 ? 7 : high;
    if (low + high > 7) high = 7 - low;  // a piece thinner than an eighth keeps one eighth
    code = uint16_t(code | (low << (2 + 6 * k)) | (high << (5 + 6 * k)));
  }
  return code;
}

// False for codes the format does not allow (axis 3, bit 15, an interval under an eighth).
inline bool isValidExtent(uint16_t code) {
  if ((code & 3u) == 3u || (code >> 15) != 0) return false;
  for (int k = 0; k < 2; ++k)
    if (((code >> (2 + 6 * k)) & 7u) + ((code >> (5 + 6 * k)) & 7u) > 7u) return false;
  return true;
}

inline FragmentExtent decodeExtent(uint16_t code) {
  FragmentExtent e;
  e.axis = int(code & 3u);
  e.convex = (code & kExtentConvex) != 0;
  for (int k = 0; k < 2; ++k) {
    e.lo[k] = double((code >> (2 + 6 * k)) & 7u) / kExtentSteps;
    e.hi[k] = 1.0 - double((code >> (5 + 6 * k)) & 7u) / kExtentSteps;
  }
  return e;
}

// Whether a point (voxel-local, [0, 1]^3) lies in the extent's box grown by kExtentTolerance. A
// bound on the voxel's face is no bound: a hit inside the chord may round to just outside the
// voxel, and code 0 must keep every hit, as in version 2.1.
inline bool extentHolds(const FragmentExtent& e, const std::array<double, 3>& local) {
  for (int k = 0; k < 2; ++k) {
    const double x = local[(e.axis + 1 + k) % 3];
    if ((e.lo[k] > 0 && x < e.lo[k] - kExtentTolerance) ||
        (e.hi[k] < 1 && x > e.hi[k] + kExtentTolerance))
      return false;
  }
  return true;
}

}  // namespace voxlink::format
