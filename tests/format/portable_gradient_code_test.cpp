// SPDX-License-Identifier: BSD-3-Clause
// The float encoder packed files predict with (pack/detail/portable_gradient_code.h): it agrees
// with the float64 reference except within its arithmetic's error of a cell border, a batch gives
// the same codes as one direction at a time (the vectorized loop and its scalar remainder), and
// zero, non-finite, tiny and huge input behave.
#include "pack/detail/portable_gradient_code.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <vector>

#include "format/gradient_codec.h"

namespace voxlink::pack {

using format::encodeGradientReference;
using format::kAzimuthSteps;
using format::kPolarSteps;
using format::kZeroGradient;

namespace {

uint16_t portableCode(float x, float y, float z) {
  uint16_t code;
  portableGradientCodes(&x, &y, &z, &code, 1);
  return code;
}

// How far (in radians) the direction lies from the nearest border between cells of the
// reference encoder: polar borders at (t + 0.5) pi / 254, azimuth borders at (p + 0.5) pi / 128.
double distanceToBorder(double x, double y, double z) {
  const double polar = std::atan2(std::hypot(x, y), z);
  const double polarStep = std::numbers::pi / kPolarSteps;
  const double dp = std::abs(std::remainder(polar - 0.5 * polarStep, polarStep));
  double azimuth = std::atan2(y, x);
  const double azimuthStep = 2 * std::numbers::pi / kAzimuthSteps;
  const double da = std::abs(std::remainder(azimuth - 0.5 * azimuthStep, azimuthStep));
  // An azimuth error matters by sin(polar) on the sphere; near the poles it does not matter.
  return std::min(dp, da / std::max(std::sin(polar), 1e-12));
}

TEST(PortableGradientCode, AgreesWithTheReferenceAwayFromCellBorders) {
  std::mt19937_64 rng(7);
  std::normal_distribution<float> normal;
  constexpr int kDirections = 400000;
  int different = 0;
  double nearestDifferent = 0;
  for (int i = 0; i < kDirections; ++i) {
    const float x = normal(rng), y = normal(rng), z = normal(rng);
    const uint16_t reference = encodeGradientReference(x, y, z);
    if (portableCode(x, y, z) == reference) continue;
    ++different;
    nearestDifferent = std::max(nearestDifferent, distanceToBorder(x, y, z));
  }
  // Float arctangents err by about 1e-7 rad: only directions that close to a border may differ
  // (11 of 400,000 here, the farthest 1.2e-7 rad from its border; a change of 3e-5 in one
  // polynomial coefficient gives 16 and 7.2e-7).
  EXPECT_LE(different, kDirections / 20000) << different;
  EXPECT_LT(nearestDifferent, 5e-7) << different << " differ";
}

TEST(PortableGradientCode, IntegerDifferencesAsInCtAgree) {
  // Central differences of 8-bit CT values are half-integers: they match the reference but
  // within rounding of a border.
  int different = 0, total = 0;
  for (int x = -40; x <= 40; x += 3)
    for (int y = -40; y <= 40; y += 3)
      for (int z = -40; z <= 40; z += 3) {
        ++total;
        const uint16_t reference = encodeGradientReference(0.5 * x, 0.5 * y, 0.5 * z);
        if (portableCode(0.5f * x, 0.5f * y, 0.5f * z) != reference) {
          ++different;
          EXPECT_LT(distanceToBorder(x, y, z), 5e-7) << x << " " << y << " " << z;
        }
      }
  EXPECT_LE(different, total / 1000) << different << " of " << total;
}

TEST(PortableGradientCode, BatchEqualsOneAtATime) {
  // Long batches run the vectorized loop, single calls its scalar remainder: the same bits.
  std::mt19937_64 rng(3);
  std::normal_distribution<float> normal;
  std::uniform_real_distribution<float> exponent(-40, 40);
  constexpr uint32_t kCount = 100003;
  std::vector<float> x(kCount), y(kCount), z(kCount);
  for (uint32_t i = 0; i < kCount; ++i) {
    const float scale = std::pow(2.0f, exponent(rng));
    x[i] = normal(rng) * scale;
    y[i] = normal(rng) * scale;
    z[i] = i % 17 == 0 ? 0.0f : normal(rng) * scale;  // some in the equator's plane
  }
  std::vector<uint16_t> batch(kCount);
  portableGradientCodes(x.data(), y.data(), z.data(), batch.data(), kCount);
  for (uint32_t i = 0; i < kCount; ++i)
    ASSERT_EQ(batch[i], portableCode(x[i], y[i], z[i]))
        << i << ": " << x[i] << " " << y[i] << " " << z[i];
}

TEST(PortableGradientCode, AxesPolesZeroAndExtremes) {
  EXPECT_EQ(portableCode(0, 0, 1), encodeGradientReference(0, 0, 1));
  EXPECT_EQ(portableCode(0, 0, -1), encodeGradientReference(0, 0, -1));
  EXPECT_EQ(portableCode(1, 0, 0), encodeGradientReference(1, 0, 0));
  EXPECT_EQ(portableCode(-1, 0, 0), encodeGradientReference(-1, 0, 0));
  EXPECT_EQ(portableCode(0, 1, 0), encodeGradientReference(0, 1, 0));
  EXPECT_EQ(portableCode(0, -1, 0), encodeGradientReference(0, -1, 0));
  EXPECT_EQ(portableCode(-1, -0.0f, 0), encodeGradientReference(-1, -0.0, 0));
  EXPECT_EQ(portableCode(0, 0, 0), kZeroGradient);
  const float inf = std::numeric_limits<float>::infinity();
  const float nan = std::numeric_limits<float>::quiet_NaN();
  EXPECT_EQ(portableCode(nan, 1, 0), kZeroGradient);
  EXPECT_EQ(portableCode(0, inf, 0), kZeroGradient);
  EXPECT_EQ(portableCode(0, 0, -inf), kZeroGradient);
  // Scale does not matter, from the smallest normal float to the largest; below that (where a
  // thread flushing subnormals would read zero) the gradient counts as zero.
  const float smallest = std::numeric_limits<float>::min();
  const float huge = std::numeric_limits<float>::max();
  EXPECT_EQ(portableCode(3 * smallest, 2 * smallest, smallest), portableCode(3, 2, 1));
  EXPECT_EQ(portableCode(smallest / 2, 0, 0), kZeroGradient);
  EXPECT_EQ(portableCode(0, 0, -std::numeric_limits<float>::denorm_min()), kZeroGradient);
  EXPECT_EQ(portableCode(huge, -huge / 2, huge / 4), portableCode(4, -2, 1));
  EXPECT_EQ(portableCode(-huge, 0, 0), encodeGradientReference(-1, 0, 0));
}

// The codes are part of the packed format (codec 4): files packed with them unpack only while
// this encoder gives the same bits. Directions from a fixed integer sequence (no library
// distribution, whose output the standard leaves open), hashed; a different hash means every
// file packed with codec 4 so far would be refused. (tests/data/packed/v2 pins it on real data
// too, but its few thousand voxels may not reach a changed border.)
TEST(PortableGradientCode, CodesArePinned) {
  constexpr uint32_t kCount = 1 << 20;
  std::vector<float> x(kCount), y(kCount), z(kCount);
  uint64_t state = 0x9E3779B97F4A7C15ull;
  auto next = [&] {  // an integer in [-2^20, 2^20), then as a float: exact
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return static_cast<float>(static_cast<int32_t>(state >> 43) - (1 << 20));
  };
  for (uint32_t i = 0; i < kCount; ++i) {
    // Some of them as small integers, like central differences of 8-bit values.
    const float scale = i % 4 == 0 ? 1.0f / 4096.0f : 1.0f;
    x[i] = std::round(next() * scale) * 0.5f;
    y[i] = std::round(next() * scale) * 0.5f;
    z[i] = std::round(next() * scale) * 0.5f;
  }
  std::vector<uint16_t> codes(kCount);
  portableGradientCodes(x.data(), y.data(), z.data(), codes.data(), kCount);
  uint64_t hash = 1469598103934665603ull;  // FNV-1a
  for (const uint16_t c : codes) hash = (hash ^ c) * 1099511628211ull;
  EXPECT_EQ(hash, 0x59e2e512c1458dfeull) << std::hex << hash;
}

}  // namespace
}  // namespace voxlink::pack
