// SPDX-License-Identifier: BSD-3-Clause
#include "format/gradient_codec.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

namespace voxlink::format {
namespace {

// cos of the polar cell boundaries: the code's t is the number of boundaries above z.
// Boundary tables carry sentinels at both ends so the encoder's corrections need no range
// checks: cosBoundary[k + 1] = cos((k + 0.5) pi / 254), cosBoundary[0] = +inf, [255] = -inf;
// tanBoundary[j + 1] = tan((j + 0.5) pi / 128), tanBoundary[0] = -inf, [33] = +inf.
struct PolarTables {
  double cosBoundary[kPolarSteps + 2];
  double tanBoundary[kAzimuthSteps / 8 + 2];
  float sinTheta[kPolarSteps + 1], cosTheta[kPolarSteps + 1];
  float sinPhi[kAzimuthSteps], cosPhi[kAzimuthSteps];
};

PolarTables makeTables() {
  {
    PolarTables r{};
    const double pi = std::numbers::pi;
    const double inf = std::numeric_limits<double>::infinity();
    r.cosBoundary[0] = inf;
    r.cosBoundary[kPolarSteps + 1] = -inf;
    for (int k = 0; k < kPolarSteps; ++k)
      r.cosBoundary[k + 1] = std::cos((k + 0.5) * pi / kPolarSteps);
    r.tanBoundary[0] = -inf;
    r.tanBoundary[kAzimuthSteps / 8 + 1] = inf;
    for (int j = 0; j < kAzimuthSteps / 8; ++j)
      r.tanBoundary[j + 1] = std::tan((j + 0.5) * 2.0 * pi / kAzimuthSteps);
    for (int k = 0; k <= kPolarSteps; ++k) {
      const double theta = k * pi / kPolarSteps;
      r.sinTheta[k] = static_cast<float>(std::sin(theta));
      r.cosTheta[k] = static_cast<float>(std::cos(theta));
    }
    // Exact zeros on the axes keep axis-aligned gradients exact.
    r.sinTheta[0] = r.sinTheta[kPolarSteps] = 0.0f;
    r.cosTheta[kPolarSteps / 2] = 0.0f;
    for (int p = 0; p < kAzimuthSteps; ++p) {
      const double phi = p * 2.0 * pi / kAzimuthSteps;
      r.sinPhi[p] = static_cast<float>(std::sin(phi));
      r.cosPhi[p] = static_cast<float>(std::cos(phi));
    }
    for (int q = 0; q < 4; ++q) {
      const int axis = q * kAzimuthSteps / 4;
      r.sinPhi[axis] = (q == 1) ? 1.0f : (q == 3) ? -1.0f : 0.0f;
      r.cosPhi[axis] = (q == 0) ? 1.0f : (q == 2) ? -1.0f : 0.0f;
    }
    return r;
  }
}

const PolarTables kTables = makeTables();
inline const PolarTables& tables() { return kTables; }

}  // namespace

// Polynomial first guesses (errors ~1e-4 rad, far below one step of 0.0124 rad); the exact
// boundary tables then correct the guess by at most a step, so the result is the same as a
// binary search over the boundaries, without its unpredictable branches.
inline double acosGuess(double x) {  // Abramowitz & Stegun 4.4.45, |error| <= 6.7e-5
  const double a = std::abs(x);
  const double r =
      std::sqrt(1.0 - a) * (1.5707288 + a * (-0.2121144 + a * (0.0742610 - 0.0187293 * a)));
  return x >= 0 ? r : std::numbers::pi - r;
}

inline double atanGuess(double r) {  // r in [0, 1], |error| < 1.5e-3
  return r * (std::numbers::pi / 4) - r * (r - 1.0) * (0.2447 + 0.0663 * r);
}

uint16_t encodeGradient(double x, double y, double z) {
  if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z)) return kZeroGradient;
  // Scale by the largest component first so squares neither overflow nor underflow.
  const double big = std::max({std::abs(x), std::abs(y), std::abs(z)});
  if (big == 0.0) return kZeroGradient;
  if (big > 0x1p500 || big < 0x1p-500) {  // rescale only where squares could over/underflow
    const double inv = 1.0 / big;
    x *= inv;
    y *= inv;
    z *= inv;
  }
  const PolarTables& t = tables();

  // theta step = number of polar boundaries whose cosine lies above z/length.
  const double zn = z / std::sqrt(x * x + y * y + z * z);
  int theta = static_cast<int>(acosGuess(zn) * (kPolarSteps / std::numbers::pi) + 0.5);
  theta = std::clamp(theta, 0, kPolarSteps);
  // The guess is off by at most one step; the sentinels make both tests safe at the ends.
  theta += zn < t.cosBoundary[theta + 1];
  theta -= !(zn < t.cosBoundary[theta]);
  if (theta == 0 || theta == kPolarSteps) return static_cast<uint16_t>(theta << 8);

  // phi step: reduce to the first octant, count the tangent boundaries below, unfold.
  const double ax = std::abs(x), ay = std::abs(y);
  const bool steep = ay > ax;
  const double ratio = steep ? ax / ay : ay / ax;
  constexpr int kOctant = kAzimuthSteps / 8;
  int j = static_cast<int>(atanGuess(ratio) * (kAzimuthSteps / (2 * std::numbers::pi)) + 0.5);
  j = std::clamp(j, 0, kOctant);
  j += ratio > t.tanBoundary[j + 1];
  j -= !(ratio > t.tanBoundary[j]);
  int phi = steep ? kAzimuthSteps / 4 - j : j;             // first quadrant, 0..64
  if (x < 0) phi = kAzimuthSteps / 2 - phi;                // mirror across the y axis
  if (y < 0) phi = (kAzimuthSteps - phi) % kAzimuthSteps;  // mirror across the x axis
  return static_cast<uint16_t>(theta << 8 | (phi & 0xFF));
}

namespace {

// atan(lo / hi) for 0 <= lo <= hi, hi > 0, to a few float ulps: range reduction about pi/8
// folded into the one division, then the Cephes atanf minimax polynomial. Branch-free, so
// loops over it vectorize.
__attribute__((always_inline)) inline float atanRatio(float lo, float hi) {
  const bool big =
      lo > 0.41421356237309505f * hi;  // ratio > tan(pi/8): atan(r) = pi/4 + atan((r-1)/(r+1))
  const float x = (big ? lo - hi : lo) / (big ? lo + hi : hi);
  const float z = x * x;
  const float p = (((8.05374449538e-2f * z - 1.38776856032e-1f) * z + 1.99777106478e-1f) * z -
                   3.33329491539e-1f) *
                      z * x +
                  x;
  return big ? 0.78539816339744831f + p : p;
}

// The encoding loop; the compiler vectorizes it. Both angles come from octant-reduced arctangents
// (one square root, two divisions per lane): the polar angle as atan2(sqrt(x^2 + y^2), z), the
// azimuth from the first-octant ratio.
__attribute__((always_inline)) inline void encodeLoop(const float* __restrict gx,
                                                      const float* __restrict gy,
                                                      const float* __restrict gz,
                                                      uint16_t* __restrict codes, size_t count) {
  constexpr float kPi = 3.14159265358979323846f;
  constexpr float kHalfPi = 1.57079632679489662f;
  constexpr float kMaxFloat = std::numeric_limits<float>::max();
  for (size_t i = 0; i < count; ++i) {
    float x = gx[i], y = gy[i], z = gz[i];
    const float big = std::max(std::abs(x), std::max(std::abs(y), std::abs(z)));
    // False for zero, inf and NaN (std::max can pass over a NaN component; the sum cannot).
    const float sum = x + y + z;
    const bool valid = big > 0.0f && big <= kMaxFloat && sum == sum;
    // Squares must neither overflow nor vanish: rescale by an exact power of two, only when
    // the vector is huge or tiny (no division, so the common case costs a compare).
    const float rescale = big > 0x1p60f ? 0x1p-100f : (big < 0x1p-60f ? 0x1p100f : 1.0f);
    x = valid ? x * rescale : 0.0f;
    y = valid ? y * rescale : 0.0f;
    z = valid ? z * rescale : 1.0f;
    const float rho = std::sqrt(x * x + y * y), az = std::abs(z);
    const float t = atanRatio(std::min(rho, az), std::max(rho, az));
    const float fromAxis = rho <= az ? t : kHalfPi - t;
    const float polar = z >= 0.0f ? fromAxis : kPi - fromAxis;
    int32_t theta = static_cast<int32_t>(polar * (kPolarSteps / kPi) + 0.5f);
    theta = std::min(std::max(theta, 0), int32_t{kPolarSteps});
    // Azimuth: the first-octant angle, unfolded by the signs and the larger component.
    const float sx = std::abs(x), sy = std::abs(y);
    const float lo = std::min(sx, sy), hi = std::max(sx, sy);
    int32_t j = static_cast<int32_t>(
        atanRatio(lo, hi > 0.0f ? hi : 1.0f) * (kAzimuthSteps / (2 * kPi)) + 0.5f);
    j = std::min(std::max(j, 0), int32_t{kAzimuthSteps / 8});
    int32_t phi = sy > sx ? kAzimuthSteps / 4 - j : j;
    phi = x < 0 ? kAzimuthSteps / 2 - phi : phi;
    phi = y < 0 ? (kAzimuthSteps - phi) & 0xFF : phi;
    phi = (theta == 0 || theta == kPolarSteps) ? 0 : phi;
    codes[i] = static_cast<uint16_t>(valid ? (theta << 8 | phi) : kZeroGradient);
  }
}

// The whole batch encoder, compiled for several instruction sets and picked once at run time.
// The tail is padded to a full vector so it runs the same vector code, not a scalar epilogue.
constexpr size_t kTail = 16;

__attribute__((always_inline)) inline void encodeBatchBody(const float* __restrict gx,
                                                           const float* __restrict gy,
                                                           const float* __restrict gz,
                                                           uint16_t* __restrict codes,
                                                           size_t count) {
  const size_t body = count / kTail * kTail, rest = count - body;
  encodeLoop(gx, gy, gz, codes, body);
  if (rest == 0) return;
  float x[kTail] = {}, y[kTail] = {}, z[kTail] = {};
  uint16_t tail[kTail];
  for (size_t i = 0; i < rest; ++i) x[i] = gx[body + i], y[i] = gy[body + i], z[i] = gz[body + i];
  encodeLoop(x, y, z, tail, kTail);
  for (size_t i = 0; i < rest; ++i) codes[body + i] = tail[i];
}

using EncodeBatchFn = void (*)(const float*, const float*, const float*, uint16_t*, size_t);

void encodeBatchPortable(const float* gx, const float* gy, const float* gz, uint16_t* codes,
                         size_t count) {
  encodeBatchBody(gx, gy, gz, codes, count);
}

#if defined(__x86_64__)
// Explicit ISA lists rather than target_clones("arch=..."): an arch clone may not inline the
// std:: helpers, which leaves calls in the loop and stops the vectorizer.
__attribute__((target("avx2,fma"))) void encodeBatchAvx2(const float* gx, const float* gy,
                                                         const float* gz, uint16_t* codes,
                                                         size_t count) {
  encodeBatchBody(gx, gy, gz, codes, count);
}

__attribute__((target("avx512f,avx512vl,avx512bw,avx512dq,avx2,fma"))) void encodeBatchAvx512(
    const float* gx, const float* gy, const float* gz, uint16_t* codes, size_t count) {
  encodeBatchBody(gx, gy, gz, codes, count);
}
#endif

std::vector<BatchGradientEncoder> availableEncoders() {
  std::vector<BatchGradientEncoder> list;
#if defined(__x86_64__)
  __builtin_cpu_init();  // this runs during static initialization, maybe before libgcc's own
  if (__builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl") &&
      __builtin_cpu_supports("avx512bw") && __builtin_cpu_supports("avx512dq"))
    list.push_back({"avx512", encodeBatchAvx512});
  if (__builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma"))
    list.push_back({"avx2", encodeBatchAvx2});
#endif
  list.push_back({"portable", encodeBatchPortable});
  return list;
}

const EncodeBatchFn encodeBatch = availableEncoders().front().encode;

}  // namespace

void encodeGradients(const float* x, const float* y, const float* z, uint16_t* codes,
                     size_t count) {
  encodeBatch(x, y, z, codes, count);
}

std::vector<BatchGradientEncoder> batchGradientEncoders() { return availableEncoders(); }

uint16_t encodeGradient(float x, float y, float z) {
  return encodeGradient(double{x}, double{y}, double{z});
}

std::array<float, 3> decodeGradient(uint16_t code) {
  const int theta = code >> 8;
  const int phi = code & 0xFF;
  if (theta > kPolarSteps) return {0.0f, 0.0f, 0.0f};
  const PolarTables& t = tables();
  const float s = t.sinTheta[theta];
  return {s * t.cosPhi[phi], s * t.sinPhi[phi], t.cosTheta[theta]};
}

bool isCanonicalGradientCode(uint16_t code) {
  if (code == kZeroGradient) return true;
  const int theta = code >> 8;
  const int phi = code & 0xFF;
  if (theta > kPolarSteps) return false;
  if ((theta == 0 || theta == kPolarSteps) && phi != 0) return false;
  return true;
}

uint16_t encodeGradientReference(double x, double y, double z) {
  if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z)) return kZeroGradient;
  const double big = std::max({std::abs(x), std::abs(y), std::abs(z)});
  if (big == 0.0) return kZeroGradient;
  x /= big;
  y /= big;
  z /= big;
  const double pi = std::numbers::pi;
  const double length = std::sqrt(x * x + y * y + z * z);
  const double polar = std::acos(std::clamp(z / length, -1.0, 1.0));
  const int theta = static_cast<int>(std::lround(polar * kPolarSteps / pi));
  if (theta == 0 || theta == kPolarSteps) return static_cast<uint16_t>(theta << 8);
  double azimuth = std::atan2(y, x);
  if (azimuth < 0) azimuth += 2 * pi;
  const int phi = static_cast<int>(std::lround(azimuth * kAzimuthSteps / (2 * pi))) % kAzimuthSteps;
  return static_cast<uint16_t>(theta << 8 | phi);
}

}  // namespace voxlink::format
