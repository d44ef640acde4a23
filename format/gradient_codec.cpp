#include "format/gradient_codec.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace voxlink::format {
namespace {

// cos of the polar cell boundaries: the code's t is the number of boundaries above z.
struct PolarTables {
  double cosBoundary[kPolarSteps];            // cos((k + 0.5) * pi / 254), decreasing
  double tanBoundary[kAzimuthSteps / 8];      // tan((j + 0.5) * pi / 128), j = 0..31
  float sinTheta[kPolarSteps + 1], cosTheta[kPolarSteps + 1];
  float sinPhi[kAzimuthSteps], cosPhi[kAzimuthSteps];
};

const PolarTables& tables() {
  static const PolarTables t = [] {
    PolarTables r{};
    const double pi = std::numbers::pi;
    for (int k = 0; k < kPolarSteps; ++k) r.cosBoundary[k] = std::cos((k + 0.5) * pi / kPolarSteps);
    for (int j = 0; j < kAzimuthSteps / 8; ++j)
      r.tanBoundary[j] = std::tan((j + 0.5) * 2.0 * pi / kAzimuthSteps);
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
  }();
  return t;
}

}  // namespace

uint16_t encodeGradient(double x, double y, double z) {
  if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z)) return kZeroGradient;
  // Scale by the largest component first so squares neither overflow nor underflow.
  const double big = std::max({std::abs(x), std::abs(y), std::abs(z)});
  if (big == 0.0) return kZeroGradient;
  x /= big;
  y /= big;
  z /= big;
  const double length = std::sqrt(x * x + y * y + z * z);
  const PolarTables& t = tables();

  // theta step: count boundaries whose cosine lies above z/length (binary search).
  const double zn = z / length;
  int lo = 0, hi = kPolarSteps;  // answer in [lo, hi]
  while (lo < hi) {
    const int mid = (lo + hi) / 2;
    if (zn < t.cosBoundary[mid]) lo = mid + 1; else hi = mid;
  }
  const int theta = lo;
  if (theta == 0 || theta == kPolarSteps) return static_cast<uint16_t>(theta << 8);

  // phi step: reduce to the first octant, search the tangent boundaries, unfold.
  const double ax = std::abs(x), ay = std::abs(y);
  const bool steep = ay > ax;
  const double ratio = steep ? ax / ay : ay / ax;
  int j = 0;
  lo = 0;
  hi = kAzimuthSteps / 8;
  while (lo < hi) {
    const int mid = (lo + hi) / 2;
    if (ratio > t.tanBoundary[mid]) lo = mid + 1; else hi = mid;
  }
  j = lo;                                          // 0..32, steps from the nearer axis
  int phi = steep ? kAzimuthSteps / 4 - j : j;     // first quadrant, 0..64
  if (x < 0) phi = kAzimuthSteps / 2 - phi;        // mirror across the y axis
  if (y < 0) phi = (kAzimuthSteps - phi) % kAzimuthSteps;  // mirror across the x axis
  return static_cast<uint16_t>(theta << 8 | (phi & 0xFF));
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
