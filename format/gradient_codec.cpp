#include "format/gradient_codec.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>
#include <numbers>

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
    for (int k = 0; k < kPolarSteps; ++k) r.cosBoundary[k + 1] = std::cos((k + 0.5) * pi / kPolarSteps);
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
  const double r = std::sqrt(1.0 - a) * (1.5707288 + a * (-0.2121144 + a * (0.0742610 - 0.0187293 * a)));
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



// Float arcsine on [0, 1] and arctangent on [0, 1] accurate to a few float ulps (Cephes-style
// minimax polynomials with range reduction), branch-free so loops over them vectorize.
inline float asinUnit(float a) {  // a in [0, 1]
  const bool big = a > 0.5f;
  const float z = big ? 0.5f * (1.0f - a) : a * a;
  const float x = big ? std::sqrt(z) : a;
  const float p = ((((4.2163199048e-2f * z + 2.4181311049e-2f) * z + 4.5470025998e-2f) * z + 7.4953002686e-2f) * z +
                   1.6666752422e-1f) * z * x + x;
  return big ? 1.5707963267948966f - 2.0f * p : p;
}

inline float atanUnit(float r) {  // r in [0, 1]
  const bool big = r > 0.4142135623730950f;  // tan(pi/8)
  const float x = big ? (r - 1.0f) / (r + 1.0f) : r;
  const float z = x * x;
  const float p = (((8.05374449538e-2f * z - 1.38776856032e-1f) * z + 1.99777106478e-1f) * z - 3.33329491539e-1f) * z * x + x;
  return big ? 0.7853981633974483f + p : p;
}

// The whole batch encoder: branch-free float arithmetic the compiler vectorizes (AVX2 clone
// where the CPU has it). Rounding to the nearest step is exact up to float rounding.
__attribute__((target_clones("avx2", "default"))) void encodeBatch(const float* __restrict gx,
                                                                 const float* __restrict gy,
                                                                 const float* __restrict gz,
                                                                 uint16_t* __restrict codes, size_t count) {
  constexpr float kPi = 3.14159265358979323846f;
  constexpr float kMaxFloat = std::numeric_limits<float>::max();
  for (size_t i = 0; i < count; ++i) {
    float x = gx[i], y = gy[i], z = gz[i];
    const float big = std::max(std::abs(x), std::max(std::abs(y), std::abs(z)));
    const bool valid = big > 0.0f && big <= kMaxFloat;  // false for zero, inf and NaN
    // Squares must neither overflow nor vanish: rescale by an exact power of two, only when
    // the vector is huge or tiny (no division, so the common case costs a compare).
    const float rescale = big > 0x1p60f ? 0x1p-100f : (big < 0x1p-60f ? 0x1p100f : 1.0f);
    x *= rescale;
    y *= rescale;
    z = valid ? z * rescale : 1.0f;
    const float zn = std::min(1.0f, std::max(-1.0f, z / std::sqrt(x * x + y * y + z * z)));
    // Polar angle from +z: acos(zn) = pi/2 - asin(zn).
    const float asinAbs = asinUnit(std::abs(zn));
    const float polar = zn >= 0.0f ? 1.5707963267948966f - asinAbs : 1.5707963267948966f + asinAbs;
    int32_t theta = static_cast<int32_t>(polar * (kPolarSteps / kPi) + 0.5f);
    theta = std::min(std::max(theta, 0), int32_t{kPolarSteps});
    // Azimuth: the first-octant angle, unfolded by the signs and the larger component.
    const float sx = std::abs(x), sy = std::abs(y);
    const float lo = std::min(sx, sy), hi = std::max(sx, sy);
    const float ratio = lo / (hi > 0.0f ? hi : 1.0f);
    int32_t j = static_cast<int32_t>(atanUnit(ratio) * (kAzimuthSteps / (2 * kPi)) + 0.5f);
    j = std::min(std::max(j, 0), int32_t{kAzimuthSteps / 8});
    int32_t phi = sy > sx ? kAzimuthSteps / 4 - j : j;
    phi = x < 0 ? kAzimuthSteps / 2 - phi : phi;
    phi = y < 0 ? (kAzimuthSteps - phi) & 0xFF : phi;
    phi = (theta == 0 || theta == kPolarSteps) ? 0 : phi;
    codes[i] = static_cast<uint16_t>(valid ? (theta << 8 | phi) : kZeroGradient);
  }
}

}  // namespace

void encodeGradients(const float* x, const float* y, const float* z, uint16_t* codes, size_t count) {
  encodeBatch(x, y, z, codes, count);
}

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
