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

// Per-direction intermediate results of the vectorized half of encodeGradients().
struct EncodeScratch {
  std::vector<float> zn, ratio;
  std::vector<int32_t> theta, j, flags;
  void resize(size_t n) {
    zn.resize(n);
    ratio.resize(n);
    theta.resize(n);
    j.resize(n);
    flags.resize(n);
  }
};

enum : int32_t { kValid = 1, kSteep = 2, kNegX = 4, kNegY = 8 };

// Branch-free float arithmetic: first guesses of the polar and azimuth steps.
__attribute__((target_clones("avx2", "default"))) void guessSteps(
    const float* __restrict gx, const float* __restrict gy, const float* __restrict gz, size_t count,
    float* __restrict znOut, float* __restrict ratioOut, int32_t* __restrict thetaOut,
    int32_t* __restrict jOut, int32_t* __restrict flagsOut) {
  constexpr float kPi = 3.14159265358979323846f;
  constexpr float kMaxFloat = std::numeric_limits<float>::max();
  for (size_t i = 0; i < count; ++i) {
    float x = gx[i], y = gy[i], z = gz[i];
    float big = std::max(std::abs(x), std::max(std::abs(y), std::abs(z)));
    const bool valid = big > 0.0f && big <= kMaxFloat;  // false for zero, inf and NaN
    // Lift tiny (subnormal) vectors by an exact power of two so 1/big stays finite.
    const float lift = big < 0x1p-60f ? 0x1p60f : 1.0f;
    x *= lift;
    y *= lift;
    z *= lift;
    big *= lift;
    const float inv = 1.0f / (valid ? big : 1.0f);  // division outside the select: vectorizes
    x *= inv;
    y *= inv;
    z = valid ? z * inv : 1.0f;
    const float zn = std::min(1.0f, std::max(-1.0f, z / std::sqrt(x * x + y * y + z * z)));
    const float a = std::abs(zn);
    const float r = std::sqrt(1.0f - a) * (1.5707288f + a * (-0.2121144f + a * (0.0742610f - 0.0187293f * a)));
    const float polar = zn >= 0.0f ? r : kPi - r;
    const float sx = std::abs(x), sy = std::abs(y);
    const float lo = std::min(sx, sy), hi = std::max(sx, sy);
    const float ratio = lo / (hi > 0.0f ? hi : 1.0f);
    const float azimuth = ratio * (kPi / 4) - ratio * (ratio - 1.0f) * (0.2447f + 0.0663f * ratio);
    znOut[i] = zn;
    ratioOut[i] = ratio;
    thetaOut[i] = static_cast<int32_t>(polar * (kPolarSteps / kPi) + 0.5f);
    jOut[i] = static_cast<int32_t>(azimuth * (kAzimuthSteps / (2 * kPi)) + 0.5f);
    flagsOut[i] = (valid ? kValid : 0) | (sy > sx ? kSteep : 0) | (x < 0 ? kNegX : 0) | (y < 0 ? kNegY : 0);
  }
}

}  // namespace

void encodeGradients(const float* x, const float* y, const float* z, uint16_t* codes, size_t count) {
  thread_local EncodeScratch s;
  s.resize(count);
  guessSteps(x, y, z, count, s.zn.data(), s.ratio.data(), s.theta.data(), s.j.data(), s.flags.data());
  const PolarTables& t = tables();
  constexpr int kOctant = kAzimuthSteps / 8;
  for (size_t i = 0; i < count; ++i) {
    const int32_t flags = s.flags[i];
    const double zn = s.zn[i], ratio = s.ratio[i];
    int theta = std::clamp(s.theta[i], 0, kPolarSteps);
    theta += zn < t.cosBoundary[theta + 1];
    theta -= !(zn < t.cosBoundary[theta]);
    int j = std::clamp(s.j[i], 0, kOctant);
    j += ratio > t.tanBoundary[j + 1];
    j -= !(ratio > t.tanBoundary[j]);
    int phi = (flags & kSteep) ? kAzimuthSteps / 4 - j : j;
    phi = (flags & kNegX) ? kAzimuthSteps / 2 - phi : phi;
    phi = (flags & kNegY) ? (kAzimuthSteps - phi) & 0xFF : phi;
    phi = (theta == 0 || theta == kPolarSteps) ? 0 : phi;
    codes[i] = (flags & kValid) ? static_cast<uint16_t>(theta << 8 | phi) : kZeroGradient;
  }
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
