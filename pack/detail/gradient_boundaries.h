// SPDX-License-Identifier: BSD-3-Clause
// The exact polar code of a direction (format/gradient_codec.h's bins), for the gradient
// predictor of packed files: the bin boundaries as compile-time cosine and sine tables and the
// search through them. Internal to pack/gradient_predictor.cpp, which inlines exactCode() into
// its loop; the tables are public there (polarBoundaryCosines() ...).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

#include "format/gradient_codec.h"

namespace voxlink::pack::detail {

using format::kAzimuthSteps;
using format::kPolarSteps;
using format::kZeroGradient;

// Compile-time cosine and sine: a fixed sequence of IEEE double operations, so every compiler
// and machine gets the same table bits (a libm call could differ in the last bit).
constexpr double kPi = 3.14159265358979323846;

constexpr double taylorCos(double x) {  // |x| <= pi/2
  double sum = 1, term = 1;
  for (int k = 1; k <= 30; ++k) {
    term *= -x * x / ((2.0 * k - 1) * (2.0 * k));
    sum += term;
  }
  return sum;
}
constexpr double taylorSin(double x) {  // |x| <= pi/2
  double sum = x, term = x;
  for (int k = 1; k <= 30; ++k) {
    term *= -x * x / ((2.0 * k) * (2.0 * k + 1));
    sum += term;
  }
  return sum;
}
constexpr double exactCos(double a) {  // 0 <= a <= pi
  return a <= kPi / 2 ? taylorCos(a) : -taylorCos(kPi - a);
}
constexpr double exactSin(double a) {  // 0 <= a <= pi
  return a <= kPi / 2 ? taylorSin(a) : taylorSin(kPi - a);
}

template <int N, bool Sine>
constexpr std::array<double, N> boundaryTable(int steps) {
  std::array<double, N> table{};
  for (int j = 0; j < N; ++j) {
    const double angle = (j + 0.5) * kPi / steps;
    table[j] = Sine ? exactSin(angle) : exactCos(angle);
  }
  return table;
}

// Polar index t = number of boundaries j with cos(theta) < kPolar[j].
constexpr auto kPolar = boundaryTable<kPolarSteps, false>(kPolarSteps);
// Azimuth in the upper half plane: q = number of boundaries j below the direction's angle.
constexpr int kHalfTurn = kAzimuthSteps / 2;
constexpr auto kAzimuthCos = boundaryTable<kHalfTurn, false>(kHalfTurn);
constexpr auto kAzimuthSin = boundaryTable<kHalfTurn, true>(kHalfTurn);

// exactGradientCode, inlined into the prediction's loop.
inline uint16_t exactCode(double x, double y, double z, uint16_t guess) {
  const double big = std::max({std::abs(x), std::abs(y), std::abs(z)});
  if (!(big > 0) || !std::isfinite(big)) return kZeroGradient;
  if (big > 1e100 || big < 1e-100) x /= big, y /= big, z /= big;  // squares stay finite
  // cos(theta) < kPolar[j] as z < kPolar[j] * length: no division.
  const double length = std::sqrt(x * x + y * y + z * z);
  int t = guess == kZeroGradient ? kPolarSteps / 2 : std::min(guess >> 8, kPolarSteps);
  while (t > 0 && !(z < kPolar[t - 1] * length)) --t;
  while (t < kPolarSteps && z < kPolar[t] * length) ++t;
  if (t == 0 || t == kPolarSteps) return static_cast<uint16_t>(t << 8);
  // Azimuth: fold the lower half plane onto the upper one (negation is exact), then find how
  // many boundary directions lie clockwise of (x, y) by the sign of their cross product.
  const bool lower = y < 0;
  const double ax = lower ? -x : x, ay = lower ? -y : y;
  int q = guess == kZeroGradient ? 0 : (guess & 0xFF) - (lower ? kHalfTurn : 0);
  q = std::clamp(q, 0, kHalfTurn);
  auto above = [&](int j) { return kAzimuthCos[j] * ay - kAzimuthSin[j] * ax > 0; };
  while (q > 0 && !above(q - 1)) --q;
  while (q < kHalfTurn && above(q)) ++q;
  const int p = (q + (lower ? kHalfTurn : 0)) % kAzimuthSteps;
  return static_cast<uint16_t>(t << 8 | p);
}

}  // namespace voxlink::pack::detail
