// SPDX-License-Identifier: BSD-3-Clause
#include "pack/detail/portable_gradient_code.h"

#include <cmath>

#include "base/vector_clones.h"
#include "format/gradient_codec.h"

namespace voxlink::pack {

using format::kAzimuthSteps;
using format::kPolarSteps;
using format::kZeroGradient;

namespace {

// The angle of (x, y) from +x towards +y, in [0, 2 pi]: Cephes' atanf of min(|x|, |y|) /
// max(|x|, |y|) (reduced at tan(pi/8) to (min - max) / (min + max) plus pi/4; a degree-9 odd
// polynomial), then unfolded by octant. One division; selects only, so the loop below vectorizes
// (max and min as comparisons: std::fmax's NaN rules would stop that).
inline float angleOf(float x, float y) {
  const float ax = std::fabs(x), ay = std::fabs(y);
  const float big = ax > ay ? ax : ay, small = ax > ay ? ay : ax;
  const bool high = small > 0.41421356f * big;
  const float num = high ? small - big : small, den = high ? small + big : big;
  const float r = den > 0.0f ? num / den : 0.0f;
  const float s = r * r;
  const float poly = (((8.05374449538e-2f * s - 1.38776856032e-1f) * s + 1.99777106478e-1f) * s -
                      3.33329491539e-1f) *
                         s * r +
                     r;
  float a = (high ? 0.785398163f : 0.0f) + poly;
  a = ay > ax ? 1.57079633f - a : a;
  a = x < 0.0f ? 3.14159265f - a : a;
  return y < 0.0f ? 6.28318531f - a : a;
}

}  // namespace

// Clones for wider vectors, picked when the program starts: the same operations lane by lane,
// so every clone gives the same bits (the file is built with -ffp-contract=off).
VOXLINK_VECTOR_CLONES void portableGradientCodes(const float* __restrict x,
                                                 const float* __restrict y,
                                                 const float* __restrict z,
                                                 uint16_t* __restrict codes, uint32_t count) {
  constexpr float kLargest = 3.40282347e38f;
  for (uint32_t j = 0; j < count; ++j) {
    const float ax = std::fabs(x[j]), ay = std::fabs(y[j]), az = std::fabs(z[j]);
    const float big = ax > ay ? (ax > az ? ax : az) : (ay > az ? ay : az);
    const bool finite = (ax <= kLargest) & (ay <= kLargest) & (az <= kLargest);
    // A gradient below the smallest normal float counts as zero: a thread that flushes
    // subnormals to zero (a library built with -ffast-math can switch that on) then gives the
    // same code as one that does not.
    const bool zero = !finite | !(big >= 0x1p-126f);
    // The angles depend on ratios only; a power of two (exact) keeps the squares below finite
    // and normal for very small or large input. Zero or non-finite input is replaced by zeros,
    // which give finite angles: converting NaN to int would be undefined.
    const float pre = big < 0x1p-60f ? 0x1p100f : big > 0x1p60f ? 0x1p-100f : 1.0f;
    const float gx = zero ? 0.0f : x[j] * pre, gy = zero ? 0.0f : y[j] * pre,
                gz = zero ? 0.0f : z[j] * pre;
    const float polar = angleOf(gz, std::sqrt(gx * gx + gy * gy));  // in [0, pi]
    const int t = static_cast<int>(polar * (kPolarSteps / 3.14159265f) + 0.5f);
    const int p = static_cast<int>(angleOf(gx, gy) * (kAzimuthSteps / 6.28318531f) + 0.5f) &
                  (kAzimuthSteps - 1);
    const int code = t <= 0 ? 0 : t >= kPolarSteps ? kPolarSteps << 8 : (t << 8 | p);
    codes[j] = static_cast<uint16_t>(zero ? kZeroGradient : code);
  }
}

}  // namespace voxlink::pack
