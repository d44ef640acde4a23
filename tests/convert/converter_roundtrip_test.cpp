// SPDX-License-Identifier: BSD-3-Clause
// Conversion against brute force: every kept voxel is present with its exact value, nothing
// else is stored, and every gradient is the central difference of the dense source.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "convert/converter.h"
#include "format/gradient_codec.h"
#include "format/validator.h"
#include "format/voxel_locator.h"
#include "pack/open_file.h"
#include "tests/convert/volume_fixtures.h"
#include "tests/support/test_util.h"

namespace voxlink::convert {
namespace {

// World-space central difference of the dense source, one-sided at the border (the spec).
template <class T>
std::array<double, 3> referenceGradient(const testing::MemorySource& src, uint32_t x, uint32_t y,
                                        uint32_t z) {
  const auto& info = src.info();
  const T* data = reinterpret_cast<const T*>(src.bytes().data());
  auto at = [&](uint32_t px, uint32_t py, uint32_t pz) {
    return static_cast<double>(data[(uint64_t{pz} * info.dims[1] + py) * info.dims[0] + px]);
  };
  const uint32_t p[3] = {x, y, z};
  std::array<double, 3> g{};
  for (int a = 0; a < 3; ++a) {
    uint32_t lo[3] = {x, y, z}, hi[3] = {x, y, z};
    if (p[a] > 0) --lo[a];
    if (p[a] + 1 < info.dims[a]) ++hi[a];
    const uint32_t span = hi[a] - lo[a];
    g[a] =
        span ? (at(hi[0], hi[1], hi[2]) - at(lo[0], lo[1], lo[2])) / (span * info.spacing[a]) : 0.0;
  }
  return g;
}

double angleDeg(const std::array<double, 3>& a, const std::array<float, 3>& b) {
  const double la = std::hypot(a[0], a[1], a[2]);
  const double dot = (a[0] * b[0] + a[1] * b[1] + a[2] * b[2]) / la;
  return std::acos(std::clamp(dot, -1.0, 1.0)) * 180 / std::numbers::pi;
}

template <class T>
void checkConversion(const testing::MemorySource& src, const ConvertOptions& options) {
  testing::TempDir dir;
  const std::string out = dir.file("out.vxl");
  auto& source = const_cast<testing::MemorySource&>(src);
  auto summary = convertVolume(source, options, out);
  ASSERT_TRUE(summary) << summary.message();
  auto file = pack::openFile(out);
  ASSERT_TRUE(file) << file.message();
  auto report = format::validateFile(*file);
  ASSERT_TRUE(report) << report.message();

  const auto& info = src.info();
  const T* data = reinterpret_cast<const T*>(src.bytes().data());
  format::VoxelLocator locator(*file);
  uint64_t kept = 0;
  double worstAngle = 0;
  for (uint32_t z = 0; z < info.dims[2]; ++z)
    for (uint32_t y = 0; y < info.dims[1]; ++y)
      for (uint32_t x = 0; x < info.dims[0]; ++x) {
        const double v =
            static_cast<double>(data[(uint64_t{z} * info.dims[1] + y) * info.dims[0] + x]);
        const int64_t index = locator.find(x, y, z);
        ASSERT_EQ(index >= 0, options.classification.keeps(v))
            << x << "," << y << "," << z << " v=" << v;
        if (index < 0) continue;
        ++kept;
        EXPECT_NEAR(file->value(static_cast<uint64_t>(index)), v,
                    summary->valueMaxAbsError + 1e-12);
        const auto g = referenceGradient<T>(src, x, y, z);
        const uint16_t code = file->gradientCodes()[static_cast<size_t>(index)];
        if (g[0] == 0 && g[1] == 0 && g[2] == 0) {
          EXPECT_EQ(code, format::kZeroGradient);
        } else {
          const double angle = angleDeg(g, format::decodeGradient(code));
          worstAngle = std::max(worstAngle, angle);
        }
      }
  EXPECT_EQ(kept, file->voxelCount());
  EXPECT_EQ(kept, summary->voxels);
  EXPECT_LE(worstAngle, 0.8);
  EXPECT_LE(summary->gradientMaxErrorDeg, 0.8);
}

TEST(ConverterRoundTrip, BallEveryAxisAndBrickSize) {
  auto ball = testing::makeBall({45, 38, 29});
  for (uint32_t brick : {4u, 8u, 16u, 32u}) {
    for (auto axis : {format::Axis::kX, format::Axis::kY, format::Axis::kZ}) {
      ConvertOptions o;
      o.brickSize = brick;
      o.axis = axis;
      o.classification = *thresholdClassification({"60"});
      SCOPED_TRACE(::testing::Message() << "brick " << brick << " axis " << int(axis));
      checkConversion<uint8_t>(*ball, o);
    }
  }
}

TEST(ConverterRoundTrip, AnisotropicSpacingGivesWorldSpaceGradients) {
  auto vol = testing::makeVolume<int16_t>(
      {20, 21, 22},
      [](uint32_t x, uint32_t y, uint32_t z) { return int16_t(3 * x + 2 * y * y - 5 * z - 100); },
      false, {0.5, 2.0, 3.0});
  ConvertOptions o;
  o.classification = keepAllClassification();
  checkConversion<int16_t>(*vol, o);
}

TEST(ConverterRoundTrip, UnionOfIntervalsAndTransferFunction) {
  auto ball = testing::makeBall({33, 30, 31});
  ConvertOptions o;
  o.classification = *thresholdClassification({"20,40", "150,200"});
  checkConversion<uint8_t>(*ball, o);
  auto tf = tf::parseTransferFunction(
      R"({"opacity":[[0,0],[60,0],[80,0.5],[160,0],[200,0],[230,1]]})", "tf");
  ASSERT_TRUE(tf);
  o.classification = tfClassification(*tf);
  checkConversion<uint8_t>(*ball, o);
}

TEST(ConverterRoundTrip, FloatAndDoubleSources) {
  auto f = testing::makeVolume<float>({17, 18, 19}, [](uint32_t x, uint32_t y, uint32_t z) {
    return std::sin(x * 0.3f) * std::cos(y * 0.2f) + 0.1f * z;
  });
  ConvertOptions o;
  o.classification = *keepOutsideClassification(-0.5, 0.5, std::nullopt, std::nullopt);
  checkConversion<float>(*f, o);
  auto d = testing::makeVolume<double>({17, 18, 19}, [](uint32_t x, uint32_t y, uint32_t z) {
    return std::sin(x * 0.3) * std::cos(y * 0.2) * 1e-3 + 1e-4 * z + 1.0 / 3.0;
  });
  o.classification = *thresholdClassification({"0.3335"});
  checkConversion<double>(*d, o);
}

TEST(ConverterRoundTrip, EmptyAndFullClassifications) {
  auto ball = testing::makeBall({20, 20, 20});
  ConvertOptions o;
  o.classification = *thresholdClassification({"255.5"});
  checkConversion<uint8_t>(*ball, o);
  o.classification = keepAllClassification();
  checkConversion<uint8_t>(*ball, o);
}

TEST(ConverterRoundTrip, OneVoxelThickVolumes) {
  for (std::array<uint32_t, 3> dims :
       {std::array<uint32_t, 3>{1, 9, 9}, {9, 1, 9}, {9, 9, 1}, {1, 1, 1}}) {
    auto v = testing::makeVolume<uint8_t>(
        dims, [](uint32_t x, uint32_t y, uint32_t z) { return uint8_t(10 * x + 7 * y + 3 * z); });
    ConvertOptions o;
    o.classification = keepAllClassification();
    checkConversion<uint8_t>(*v, o);
  }
}

TEST(ConverterRoundTrip, ValueTypeFollowsTheKeptRange) {
  testing::TempDir dir;
  // i16 CT values 0..3926 stay lossless in u16; a narrow kept band fits u8 with an offset.
  auto ct = testing::makeVolume<int16_t>({30, 30, 30}, [](uint32_t x, uint32_t y, uint32_t z) {
    return int16_t((x * 131 + y * 17 + z * 7) % 3927);
  });
  ConvertOptions o;
  o.classification = *thresholdClassification({"1000"});
  auto s = convertVolume(*ct, o, dir.file("a.vxl"));
  ASSERT_TRUE(s);
  EXPECT_EQ(s->storedType, StoredType::kU16);
  EXPECT_EQ(s->valueMaxAbsError, 0.0);
  o.classification = *thresholdClassification({"1000,1200"});
  s = convertVolume(*ct, o, dir.file("b.vxl"));
  ASSERT_TRUE(s);
  EXPECT_EQ(s->storedType, StoredType::kU8);
  auto file = pack::openFile(dir.file("b.vxl"));
  ASSERT_TRUE(file);
  EXPECT_EQ(file->header().valueOffset, 1000.0);
  EXPECT_EQ(file->header().valueMin, 1000.0);
  EXPECT_EQ(file->header().valueMax, 1200.0);
  checkConversion<int16_t>(*ct, o);
}

}  // namespace
}  // namespace voxlink::convert
