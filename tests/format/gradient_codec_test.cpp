// SPDX-License-Identifier: BSD-3-Clause
#include "format/gradient_codec.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <random>

namespace voxlink::format {
namespace {

double angleDegrees(const std::array<double, 3>& a, const std::array<float, 3>& b) {
  const double la = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
  const double lb = std::sqrt(double(b[0]) * b[0] + double(b[1]) * b[1] + double(b[2]) * b[2]);
  double c = (a[0] * b[0] + a[1] * b[1] + a[2] * b[2]) / (la * lb);
  c = std::clamp(c, -1.0, 1.0);
  return std::acos(c) * 180.0 / std::numbers::pi;
}

// The codec's target bound: over >= 1e6 random unit vectors, mean error <= 0.36 deg, max <= 0.8
// deg.
TEST(GradientCodec, ErrorOverAMillionRandomDirections) {
  std::mt19937_64 rng(20161122);
  std::normal_distribution<double> normal(0.0, 1.0);
  const int count = 1'000'000;
  double sum = 0, worst = 0;
  for (int i = 0; i < count; ++i) {
    const std::array<double, 3> v{normal(rng), normal(rng), normal(rng)};
    const double e = angleDegrees(v, decodeGradient(encodeGradient(v[0], v[1], v[2])));
    sum += e;
    worst = std::max(worst, e);
  }
  const double mean = sum / count;
  std::printf("[ measured ] polar16 over %d random unit vectors: mean %.4f deg, max %.4f deg\n",
              count, mean, worst);
  EXPECT_LE(mean, 0.36);
  EXPECT_LE(worst, 0.8);
}

TEST(GradientCodec, FastEncoderMatchesReferenceAwayFromBoundaries) {
  std::mt19937_64 rng(7);
  std::normal_distribution<double> normal(0.0, 1.0);
  int differ = 0;
  for (int i = 0; i < 200000; ++i) {
    const double x = normal(rng), y = normal(rng), z = normal(rng);
    const uint16_t fast = encodeGradient(x, y, z), ref = encodeGradientReference(x, y, z);
    if (fast != ref) {
      ++differ;
      // A disagreement may only pick the other of two equally near cells.
      const std::array<double, 3> v{x, y, z};
      EXPECT_NEAR(angleDegrees(v, decodeGradient(fast)), angleDegrees(v, decodeGradient(ref)),
                  1e-3);
    }
  }
  EXPECT_LT(differ, 5);
}

TEST(GradientCodec, AxisDirectionsAreExact) {
  const std::array<std::array<double, 3>, 6> axes{
      {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}}};
  for (const auto& a : axes) {
    const auto d = decodeGradient(encodeGradient(a[0], a[1], a[2]));
    for (int i = 0; i < 3; ++i) EXPECT_EQ(d[i], static_cast<float>(a[i]));
  }
}

TEST(GradientCodec, ZeroAndNonFiniteGetTheZeroCode) {
  const double inf = std::numeric_limits<double>::infinity();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(encodeGradient(0.0, 0.0, 0.0), kZeroGradient);
  EXPECT_EQ(encodeGradient(-0.0, 0.0, -0.0), kZeroGradient);
  EXPECT_EQ(encodeGradient(nan, 1.0, 0.0), kZeroGradient);
  EXPECT_EQ(encodeGradient(inf, 0.0, 0.0), kZeroGradient);
  EXPECT_EQ(encodeGradient(0.0f, -float(inf), 0.0f), kZeroGradient);
  const auto zero = decodeGradient(kZeroGradient);
  EXPECT_EQ(zero[0], 0.0f);
  EXPECT_EQ(zero[1], 0.0f);
  EXPECT_EQ(zero[2], 0.0f);
}

TEST(GradientCodec, ExtremeMagnitudesKeepTheirDirection) {
  // Neither overflow (1e300^2) nor underflow (1e-300^2) may change the direction.
  for (double scale : {1e-300, 1e-40, 1.0, 1e30, 1e300}) {
    const uint16_t code = encodeGradient(0.3 * scale, -0.5 * scale, 0.8 * scale);
    EXPECT_EQ(code, encodeGradient(0.3, -0.5, 0.8)) << scale;
  }
  EXPECT_EQ(encodeGradient(std::numeric_limits<float>::denorm_min(), 0.0f, 0.0f),
            encodeGradient(1.0f, 0.0f, 0.0f));
}

TEST(GradientCodec, EveryValidCodeDecodesToAUnitVectorAndReEncodesToItself) {
  for (uint32_t code = 0; code < 0x10000; ++code) {
    if (!isCanonicalGradientCode(static_cast<uint16_t>(code)) || code == kZeroGradient) continue;
    const auto d = decodeGradient(static_cast<uint16_t>(code));
    const double length =
        std::sqrt(double(d[0]) * d[0] + double(d[1]) * d[1] + double(d[2]) * d[2]);
    EXPECT_NEAR(length, 1.0, 1e-6) << code;
    EXPECT_EQ(encodeGradient(d[0], d[1], d[2]), code) << std::hex << code;
  }
}

TEST(GradientCodec, CanonicalForm) {
  EXPECT_TRUE(isCanonicalGradientCode(0x0000));
  EXPECT_FALSE(isCanonicalGradientCode(0x0001));  // pole with an azimuth
  EXPECT_TRUE(isCanonicalGradientCode(0xFE00));
  EXPECT_FALSE(isCanonicalGradientCode(0xFE07));
  EXPECT_FALSE(isCanonicalGradientCode(0xFF00));  // reserved
  EXPECT_TRUE(isCanonicalGradientCode(kZeroGradient));
}

}  // namespace
}  // namespace voxlink::format

namespace voxlink::format {
namespace {

TEST(GradientCodec, BatchEncoderAgreesWithScalarEncoder) {
  std::mt19937_64 rng(11);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::uniform_int_distribution<int> small(-255, 255);
  const size_t count = 300000;
  std::vector<float> x(count), y(count), z(count);
  for (size_t i = 0; i < count; ++i) {
    if (i % 2) {  // integer central differences, as from 8-bit CT
      x[i] = float(small(rng)), y[i] = float(small(rng)), z[i] = float(small(rng));
    } else {
      x[i] = float(normal(rng)), y[i] = float(normal(rng)), z[i] = float(normal(rng));
    }
  }
  // Specials: zero, non-finite, axes, huge and tiny.
  const float inf = std::numeric_limits<float>::infinity();
  const float specials[][3] = {
      {0, 0, 0},
      {inf, 0, 0},
      {0, std::nanf(""), 1},
      {1, 0, 0},
      {0, -1, 0},
      {0, 0, 1},
      {0, 0, -1},
      {3e38f, 3e38f, -3e38f},
      {1e-44f, 0, 1e-44f},
      // A NaN that std::max passes over (the largest magnitude is finite): found by fuzzing.
      {1, 1, std::nanf("")},
      {1, std::nanf(""), 0}};
  for (size_t k = 0; k < std::size(specials); ++k) {
    x[k] = specials[k][0];
    y[k] = specials[k][1];
    z[k] = specials[k][2];
  }
  for (const BatchGradientEncoder& encoder : batchGradientEncoders()) {
    SCOPED_TRACE(encoder.name);
    // Odd lengths and offsets exercise the padded tail.
    std::vector<uint16_t> codes(count);
    encoder.encode(x.data(), y.data(), z.data(), codes.data(), 7);
    encoder.encode(x.data() + 7, y.data() + 7, z.data() + 7, codes.data() + 7, count - 7);
    size_t differ = 0;
    for (size_t i = 0; i < count; ++i) {
      const uint16_t scalar = encodeGradient(double(x[i]), double(y[i]), double(z[i]));
      if (codes[i] == scalar) continue;
      ++differ;
      // A near-tie may go to either neighbouring cell; both are within the codec's bound.
      const std::array<double, 3> v{x[i], y[i], z[i]};
      EXPECT_NEAR(angleDegrees(v, decodeGradient(codes[i])),
                  angleDegrees(v, decodeGradient(scalar)), 0.01)
          << i;
      EXPECT_LE(angleDegrees(v, decodeGradient(codes[i])), 0.8) << i;
    }
    EXPECT_EQ(codes[0], kZeroGradient);
    EXPECT_EQ(codes[1], kZeroGradient);
    EXPECT_EQ(codes[2], kZeroGradient);
    EXPECT_EQ(codes[9], kZeroGradient);
    EXPECT_EQ(codes[10], kZeroGradient);
    EXPECT_LT(differ, count / 1000) << differ << " of " << count << " differ";
    std::printf(
        "[ measured ] %s batch encoder: %zu of %zu codes differ from the scalar encoder "
        "(near-ties)\n",
        encoder.name, differ, count);
  }
}

}  // namespace
}  // namespace voxlink::format
