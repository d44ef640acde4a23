// SPDX-License-Identifier: BSD-3-Clause
// The transfer function as shaders see it (tables), presets, ParaView import, and the interval
// arithmetic the viewer's classification check uses.
#include <gtest/gtest.h>

#include <random>

#include "format/half.h"
#include "tf/tf_presets.h"
#include "tf/tf_table.h"
#include "tf/value_interval.h"

namespace voxlink::tf {

namespace {

TransferFunction stepTf() {
  TransferFunction tf;
  tf.opacity = {{10, 0.0}, {20, 0.5}, {20, 0.1}, {35, 0.9}, {35.5, 0.2}};
  tf.color = {{0, {0, 0, 1}}, {20, {1, 0, 0}}, {20, {0, 1, 0}}, {50, {1, 1, 1}}};
  return tf;
}

TEST(TfTable, IndexedTablesHoldTheTfAtEveryStoredValue) {
  const TransferFunction tf = stepTf();
  const TfTable u8 = buildTfTable(tf, StoredType::kU8, 0.25, 3.0);
  ASSERT_EQ(u8.entries, 256u);
  for (uint32_t i = 0; i < 256; ++i) {
    const double v = i * 0.25 + 3.0;
    EXPECT_FLOAT_EQ(u8.texels[i * 4 + 3], float(tf.opacityAt(v))) << v;
    EXPECT_FLOAT_EQ(u8.texels[i * 4 + 0], float(tf.colorAt(v)[0])) << v;
  }
  const TfTable f16 = buildTfTable(tf, StoredType::kF16, 1.0, 0.0);
  ASSERT_EQ(f16.entries, 65536u);
  const uint16_t h = format::floatToHalf(27.5f);
  EXPECT_FLOAT_EQ(f16.texels[h * 4 + 3], float(tf.opacityAt(27.5)));
  const uint16_t nan = 0x7E00;
  EXPECT_EQ(f16.texels[nan * 4 + 3], 0.0f);
}

TEST(TfTable, BreakpointsReproduceTheTfIncludingSteps) {
  const TransferFunction tf = stepTf();
  const TfTable t = buildTfTable(tf, StoredType::kF32, 1.0, 0.0);
  EXPECT_EQ(t.kind, TfTable::Kind::kBreakpoints);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> value(-10, 60);
  std::vector<double> probes = {-5, 0, 10, 19.999, 20, 20.001, 35, 35.25, 35.5, 50, 70};
  for (int i = 0; i < 500; ++i) probes.push_back(value(rng));
  for (double v : probes) {
    const auto r = evaluateBreakpoints(t, v);
    EXPECT_NEAR(r[3], tf.opacityAt(v), 1e-6) << v;
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(r[c], tf.colorAt(v)[c], 1e-6) << v;
  }
}

TEST(TfPresets, StretchOverTheRangeAndRejectUnknownNames) {
  for (const auto& name : tfPresetNames()) {
    auto tf = tfPreset(name, 100, 300);
    ASSERT_TRUE(tf) << name;
    EXPECT_EQ(tf->opacity.front().value, 100);
    EXPECT_EQ(tf->opacity.back().value, 300);
  }
  EXPECT_EQ(tfPreset("nope", 0, 1).code(), ErrorCode::kInvalidArgument);
  EXPECT_EQ(tfPreset("ct-bone", 5, 5).code(), ErrorCode::kInvalidArgument);
}

TEST(ParaViewImport, ReadsRgbAndOpacityPointsAndRescales) {
  const std::string json = R"([
    {"Name": "Other", "RGBPoints": [0, 0, 0, 0, 1, 1, 1, 1]},
    {"Name": "Cool to Warm", "ColorSpace": "Diverging",
     "RGBPoints": [-1, 0.23, 0.299, 0.754, 0, 0.865, 0.865, 0.865, 1, 0.706, 0.016, 0.15],
     "Points": [-1, 0, 0.5, 0, 1, 0.8, 0.5, 0]}])";
  auto tf = parseParaViewPreset(json, "presets.json", {"Cool to Warm", 0, 200});
  ASSERT_TRUE(tf) << tf.message();
  EXPECT_EQ(tf->name, "Cool to Warm");
  ASSERT_EQ(tf->color.size(), 3u);
  EXPECT_DOUBLE_EQ(tf->color[1].value, 100);
  EXPECT_DOUBLE_EQ(tf->color[2].rgb[0], 0.706);
  ASSERT_EQ(tf->opacity.size(), 2u);
  EXPECT_DOUBLE_EQ(tf->opacity[1].value, 200);
  EXPECT_DOUBLE_EQ(tf->opacity[1].alpha, 0.8);
  // The first preset when no name is given; it has no Points: an opacity ramp.
  auto first = parseParaViewPreset(json, "presets.json", {});
  ASSERT_TRUE(first);
  EXPECT_EQ(first->name, "Other");
  EXPECT_EQ(first->opacity.size(), 2u);
  EXPECT_EQ(parseParaViewPreset(json, "p.json", {"Missing", 0, 1}).code(),
            ErrorCode::kInvalidArgument);
  EXPECT_FALSE(parseParaViewPreset(R"({"Name": "x", "RGBPoints": [0, 2, 0, 0]})", "p.json", {}));
  EXPECT_FALSE(parseParaViewPreset("{", "p.json", {}));
}

TEST(ClassificationCheck, IntervalArithmetic) {
  using I = ValueInterval;
  const auto merged =
      mergeIntervals({{5, 10, false, true}, {10, 12, false, false}, {1, 2, false, false}});
  ASSERT_EQ(merged.size(), 2u);
  EXPECT_EQ(merged[1].lo, 5);
  EXPECT_EQ(merged[1].hi, 12);
  // [10, 12] and (12, 20] touch at a value the first contains: one interval.
  EXPECT_EQ(mergeIntervals({{10, 12, false, false}, {12, 20, true, false}}).size(), 1u);
  // (-inf, 10) and (10, inf) leave exactly {10} out.
  const auto gap = complementIntervals({{-HUGE_VAL, 10, true, true}, {10, HUGE_VAL, true, true}});
  ASSERT_EQ(gap.size(), 1u);
  EXPECT_EQ(gap[0].lo, 10);
  EXPECT_EQ(gap[0].hi, 10);
  EXPECT_FALSE(gap[0].loOpen);
  EXPECT_TRUE(complementIntervals({{-HUGE_VAL, HUGE_VAL, true, true}}).empty());
  const auto both = intersectIntervals({I{0, 10, false, false}}, {I{5, 20, true, false}});
  ASSERT_EQ(both.size(), 1u);
  EXPECT_EQ(both[0].lo, 5);
  EXPECT_TRUE(both[0].loOpen);
  EXPECT_EQ(both[0].hi, 10);
}

}  // namespace
}  // namespace voxlink::tf
