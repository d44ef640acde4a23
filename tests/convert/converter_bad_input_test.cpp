// SPDX-License-Identifier: BSD-3-Clause
// Bad input to the converter: one clear error, the right code, and no output file left.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "convert/converter.h"
#include "tests/convert/volume_fixtures.h"
#include "tests/support/test_util.h"

namespace voxlink::convert {

using sources::VolumeSource;

namespace {

TEST(ConverterBadInput, NaNAndInfinityNameTheVoxel) {
  for (float bad :
       {std::numeric_limits<float>::quiet_NaN(), -std::numeric_limits<float>::infinity()}) {
    auto v = testing::makeVolume<float>({8, 9, 10}, [&](uint32_t x, uint32_t y, uint32_t z) {
      return (x == 3 && y == 4 && z == 7) ? bad : 1.0f;
    });
    testing::TempDir dir;
    ConvertOptions o;
    o.classification = keepAllClassification();
    auto s = convertVolume(*v, o, dir.file("out.vxl"));
    ASSERT_FALSE(s);
    EXPECT_EQ(s.code(), ErrorCode::kNonFinite);
    EXPECT_NE(s.message().find("memory: data:"), std::string::npos) << s.message();
    EXPECT_NE(s.message().find("(3, 4, 7)"), std::string::npos) << s.message();
    EXPECT_TRUE(testing::listDir(dir.path()).empty());
  }
}

TEST(ConverterBadInput, UnwritableOutputLeavesNothing) {
  auto ball = testing::makeBall({10, 10, 10});
  testing::TempDir dir;
  ConvertOptions o;
  o.classification = keepAllClassification();
  auto s = convertVolume(*ball, o, dir.file("missing/out.vxl"));
  ASSERT_FALSE(s);
  EXPECT_EQ(s.code(), ErrorCode::kIo);
  EXPECT_NE(s.message().find("missing/out.vxl"), std::string::npos);
  EXPECT_TRUE(testing::listDir(dir.path()).empty());
}

TEST(ConverterBadInput, FailureAfterTheFirstPassLeavesNoTemporaryFile) {
  // A sequential source that cannot rewind fails in pass 2, after the output was created.
  class NoRewind final : public VolumeSource {
   public:
    explicit NoRewind(testing::MemorySource& inner) : inner_(inner) { info_ = inner.info(); }
    Status read(uint32_t z0, uint32_t count, void* dst) override {
      return inner_.read(z0, count, dst);
    }
    Status rewind() override {
      if (++rewinds_ > 1) return makeError(ErrorCode::kIo, "noreweind: cannot rewind");
      return inner_.rewind();
    }

   private:
    testing::MemorySource& inner_;
    int rewinds_ = 0;
  };
  auto ball = testing::makeBall({12, 12, 12}, true);
  NoRewind source(*ball);
  testing::TempDir dir;
  ConvertOptions o;
  o.classification = keepAllClassification();
  auto s = convertVolume(source, o, dir.file("out.vxl"));
  ASSERT_FALSE(s);
  EXPECT_EQ(s.code(), ErrorCode::kIo);
  EXPECT_TRUE(testing::listDir(dir.path()).empty());
}

TEST(ConverterBadInput, BadOptions) {
  auto ball = testing::makeBall({10, 10, 10});
  testing::TempDir dir;
  ConvertOptions o;
  o.classification = keepAllClassification();
  o.brickSize = 12;
  EXPECT_EQ(convertVolume(*ball, o, dir.file("a.vxl")).code(), ErrorCode::kInvalidArgument);
  o.brickSize = 8;
  o.classification.kind = Classification::Kind::kThreshold;  // but no intervals
  EXPECT_EQ(convertVolume(*ball, o, dir.file("a.vxl")).code(), ErrorCode::kInvalidArgument);
  EXPECT_FALSE(thresholdClassification({"abc"}));
  EXPECT_FALSE(thresholdClassification({"10,5"}));
  EXPECT_FALSE(thresholdClassification({"nan"}));
  EXPECT_TRUE(testing::listDir(dir.path()).empty());
}

TEST(ConverterBadInput, CancelledConversionLeavesNothing) {
  auto ball = testing::makeBall({40, 40, 40});
  testing::TempDir dir;
  std::atomic<bool> cancel{false};
  ConvertOptions o;
  o.classification = keepAllClassification();
  o.slabSlices = 8;
  o.cancel = &cancel;
  o.progress = [&](double f, const char*) {
    if (f > 0.5) cancel = true;
  };
  auto s = convertVolume(*ball, o, dir.file("out.vxl"));
  ASSERT_FALSE(s);
  EXPECT_EQ(s.code(), ErrorCode::kCancelled);
  EXPECT_TRUE(testing::listDir(dir.path()).empty());
}

}  // namespace
}  // namespace voxlink::convert
