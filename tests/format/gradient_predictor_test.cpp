// SPDX-License-Identifier: BSD-3-Clause
// The gradient prediction of packed files: its code is decided by exact comparisons only, so it
// does not depend on the starting guess (which the vectorized encoder supplies and which may
// differ between CPUs), and it agrees with the reference encoder except on cell boundaries.
#include "pack/detail/gradient_predictor.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "format/gradient_codec.h"

namespace voxlink::pack {

using format::encodeGradientReference;
using format::kAzimuthSteps;
using format::kPolarSteps;
using format::kZeroGradient;

namespace {

TEST(GradientPredictor, BoundaryTablesAreTheCosinesAndSines) {
  const auto polar = polarBoundaryCosines();
  ASSERT_EQ(polar.size(), size_t(kPolarSteps));
  for (size_t j = 0; j < polar.size(); ++j)
    EXPECT_NEAR(polar[j], std::cos((j + 0.5) * std::numbers::pi / kPolarSteps), 1e-15) << j;
  const auto c = azimuthBoundaryCosines(), s = azimuthBoundarySines();
  ASSERT_EQ(c.size(), size_t(kAzimuthSteps / 2));
  for (size_t j = 0; j < c.size(); ++j) {
    const double a = (j + 0.5) * std::numbers::pi / (kAzimuthSteps / 2);
    EXPECT_NEAR(c[j], std::cos(a), 1e-15) << j;
    EXPECT_NEAR(s[j], std::sin(a), 1e-15) << j;
  }
}

TEST(GradientPredictor, CodeDoesNotDependOnTheGuessAndMatchesTheReference) {
  std::mt19937_64 rng(11);
  std::normal_distribution<double> normal;
  std::uniform_int_distribution<int> anyCode(0, 0xFFFF);
  int differentFromReference = 0;
  constexpr int kDirections = 200000;
  for (int i = 0; i < kDirections; ++i) {
    const double x = normal(rng), y = normal(rng), z = normal(rng);
    const uint16_t fromReference = exactGradientCode(x, y, z, encodeGradientReference(x, y, z));
    for (int g = 0; g < 3; ++g) {
      const auto guess = static_cast<uint16_t>(anyCode(rng));
      ASSERT_EQ(exactGradientCode(x, y, z, guess), fromReference)
          << "direction " << x << " " << y << " " << z << " guess " << guess;
    }
    // The scale of the vector does not matter.
    EXPECT_EQ(exactGradientCode(x * 1e200, y * 1e200, z * 1e200, 0), fromReference);
    EXPECT_EQ(exactGradientCode(x * 1e-200, y * 1e-200, z * 1e-200, 0), fromReference);
    differentFromReference += fromReference != encodeGradientReference(x, y, z);
  }
  // Only directions within rounding of a cell boundary may round the other way.
  EXPECT_LE(differentFromReference, kDirections / 10000) << differentFromReference;
}

TEST(GradientPredictor, AxesPolesAndZero) {
  for (uint16_t guess : {uint16_t(0), uint16_t(0x7F80), kZeroGradient}) {
    EXPECT_EQ(exactGradientCode(0, 0, 1, guess), encodeGradientReference(0, 0, 1));
    EXPECT_EQ(exactGradientCode(0, 0, -1, guess), encodeGradientReference(0, 0, -1));
    EXPECT_EQ(exactGradientCode(1, 0, 0, guess), encodeGradientReference(1, 0, 0));
    EXPECT_EQ(exactGradientCode(-1, 0, 0, guess), encodeGradientReference(-1, 0, 0));
    EXPECT_EQ(exactGradientCode(0, 1, 0, guess), encodeGradientReference(0, 1, 0));
    EXPECT_EQ(exactGradientCode(0, -1, 0, guess), encodeGradientReference(0, -1, 0));
    EXPECT_EQ(exactGradientCode(0, 0, 0, guess), kZeroGradient);
    EXPECT_EQ(exactGradientCode(NAN, 1, 0, guess), kZeroGradient);
    EXPECT_EQ(exactGradientCode(INFINITY, 1, 0, guess), kZeroGradient);
  }
}

}  // namespace
}  // namespace voxlink::pack
