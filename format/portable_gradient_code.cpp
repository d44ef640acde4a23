#include "format/portable_gradient_code.h"

#include <cmath>

#include "format/gradient_codec.h"

namespace voxlink::format {
namespace {

// arctan of q in [0, 1]: Cephes' atanf (reduction at tan(pi/8), degree-9 odd polynomial).
inline float arctanUnit(float q) {
  const bool high = q > 0.41421356f;
  const float r = high ? (q - 1.0f) / (q + 1.0f) : q;
  const float s = r * r;
  const float poly = (((8.05374449538e-2f * s - 1.38776856032e-1f) * s + 1.99777106478e-1f) * s -
                      3.33329491539e-1f) *
                         s * r +
                     r;
  return (high ? 0.785398163f : 0.0f) + poly;
}

// The angle of (x, y) from +x towards +y, in [0, 2 pi]. Written with selects only, so the loop
// below vectorizes (max and min as comparisons: std::fmax's NaN rules would stop that).
inline float angleOf(float x, float y) {
  const float ax = std::fabs(x), ay = std::fabs(y);
  const float big = ax > ay ? ax : ay, small = ax > ay ? ay : ax;
  float a = arctanUnit(big > 0.0f ? small / big : 0.0f);
  a = ay > ax ? 1.57079633f - a : a;
  a = x < 0.0f ? 3.14159265f - a : a;
  return y < 0.0f ? 6.28318531f - a : a;
}

}  // namespace

// Clones for wider vectors, picked when the program starts: the same operations lane by lane,
// so every clone gives the same bits (the file is built with -ffp-contract=off).
__attribute__((target_clones("avx512f", "avx2", "default"))) void portableGradientCodes(
    const float* __restrict x, const float* __restrict y, const float* __restrict z,
    uint16_t* __restrict codes, uint32_t count) {
  constexpr float kLargest = 3.40282347e38f;
  for (uint32_t j = 0; j < count; ++j) {
    const float ax = std::fabs(x[j]), ay = std::fabs(y[j]), az = std::fabs(z[j]);
    const float big = ax > ay ? (ax > az ? ax : az) : (ay > az ? ay : az);
    const bool finite = (ax <= kLargest) & (ay <= kLargest) & (az <= kLargest);
    const bool zero = !finite | !(big > 0.0f);
    // Scaled so the largest component is 1: squares neither overflow nor vanish. Very small or
    // large input is first scaled by a power of two, which is exact, so 1 / big stays finite
    // and normal.
    const float pre = big < 0x1p-100f ? 0x1p100f : big > 0x1p100f ? 0x1p-100f : 1.0f;
    const float r = zero ? 0.0f : 1.0f / (big * pre);
    const float gx = x[j] * pre * r, gy = y[j] * pre * r, gz = z[j] * pre * r;
    const float polar = angleOf(gz, std::sqrt(gx * gx + gy * gy));  // in [0, pi]
    const int t = static_cast<int>(polar * (kPolarSteps / 3.14159265f) + 0.5f);
    const int p = static_cast<int>(angleOf(gx, gy) * (kAzimuthSteps / 6.28318531f) + 0.5f) &
                  (kAzimuthSteps - 1);
    const int code = t <= 0 ? 0 : t >= kPolarSteps ? kPolarSteps << 8 : (t << 8 | p);
    codes[j] = static_cast<uint16_t>(zero ? kZeroGradient : code);
  }
}

}  // namespace voxlink::format
