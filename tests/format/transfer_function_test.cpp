// SPDX-License-Identifier: BSD-3-Clause
#include "tf/transfer_function.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace voxlink::tf {

namespace {

TransferFunction parse(const std::string& json) {
  auto tf = parseTransferFunction(json, "tf.json");
  EXPECT_TRUE(tf) << tf.message();
  return tf.isOk() ? tf.value() : TransferFunction{};
}

TEST(TransferFunction, InterpolatesAndClamps) {
  const TransferFunction tf = parse(R"({"opacity":[[0,0],[100,0.5],[200,1]],
                                        "color":[[0,0,0,0],[200,1,0.5,0]]})");
  EXPECT_DOUBLE_EQ(tf.opacityAt(-5), 0.0);
  EXPECT_DOUBLE_EQ(tf.opacityAt(50), 0.25);
  EXPECT_DOUBLE_EQ(tf.opacityAt(150), 0.75);
  EXPECT_DOUBLE_EQ(tf.opacityAt(1e9), 1.0);
  EXPECT_DOUBLE_EQ(tf.colorAt(100)[0], 0.5);
  EXPECT_DOUBLE_EQ(tf.colorAt(100)[1], 0.25);
}

TEST(TransferFunction, VisibleIntervalsAreExact) {
  const double inf = std::numeric_limits<double>::infinity();
  // A ramp from 60: 60 itself is invisible, anything above is visible.
  auto v = parse(R"({"opacity":[[60,0],[80,1]]})").visibleIntervals();
  ASSERT_EQ(v.size(), 1u);
  EXPECT_EQ(v[0].lo, 60);
  EXPECT_TRUE(v[0].loOpen);
  EXPECT_EQ(v[0].hi, inf);
  EXPECT_FALSE(v[0].contains(60));
  EXPECT_TRUE(v[0].contains(60.0001));

  // A tent with zero ends and a gap: two open intervals.
  v = parse(R"({"opacity":[[10,0],[20,1],[30,0],[40,0],[50,0.5],[60,0]]})").visibleIntervals();
  ASSERT_EQ(v.size(), 2u);
  EXPECT_EQ(describeIntervals(v), "(10, 30) u (40, 60)");

  // A step: the last point at a repeated value holds.
  const TransferFunction step = parse(R"({"opacity":[[0,0],[100,0],[100,0.8],[255,0.8]]})");
  EXPECT_DOUBLE_EQ(step.opacityAt(100), 0.8);
  EXPECT_DOUBLE_EQ(step.opacityAt(99.999), 0.0);
  v = step.visibleIntervals();
  EXPECT_EQ(describeIntervals(v), "[100, inf)");

  // Visible below the first point.
  v = parse(R"({"opacity":[[0,0.3],[10,0]]})").visibleIntervals();
  EXPECT_EQ(describeIntervals(v), "(-inf, 10)");

  // Nothing visible.
  EXPECT_TRUE(parse(R"({"opacity":[[0,0],[10,0]]})").visibleIntervals().empty());
}

TEST(TransferFunction, VisibleIntervalsAgreeWithOpacityEverywhere) {
  const TransferFunction tf =
      parse(R"({"opacity":[[0,0],[3,0],[3,0.2],[7,0],[9,0],[12,1],[12,0],[15,0]]})");
  const auto v = tf.visibleIntervals();
  for (double x = -2; x <= 17; x += 0.125) EXPECT_EQ(anyContains(v, x), tf.opacityAt(x) > 0) << x;
}

TEST(TransferFunction, BadFilesNameTheField) {
  auto r = parseTransferFunction(R"({"opacity":[[0,0],[1,2]]})", "bad.json");
  ASSERT_FALSE(r);
  EXPECT_NE(r.message().find("bad.json: field 'opacity[1]'"), std::string::npos) << r.message();
  r = parseTransferFunction(R"({"opacity":[[5,0],[1,1]]})", "bad.json");
  EXPECT_NE(r.message().find("must not decrease"), std::string::npos);
  r = parseTransferFunction("{not json", "bad.json");
  EXPECT_NE(r.message().find("not valid JSON"), std::string::npos);
  r = parseTransferFunction(R"({"color":[]})", "bad.json");
  EXPECT_NE(r.message().find("'opacity': missing"), std::string::npos);
  // Found by fuzzing: a name that is not a string threw out of the parser (abort).
  r = parseTransferFunction(R"({"name":0,"opacity":[[0,1],[1,1]],"color":[[0,0,1,1]]})",
                            "bad.json");
  ASSERT_FALSE(r);
  EXPECT_NE(r.message().find("bad.json: field 'name': expected a string"), std::string::npos)
      << r.message();
  // Another format, or a version this reader does not know, is refused; version 1 is read.
  const std::string points = R"("opacity":[[0,1],[1,1]],"color":[[0,0,1,1]])";
  r = parseTransferFunction("{\"version\":2," + points + "}", "new.json");
  ASSERT_FALSE(r);
  EXPECT_NE(r.message().find("new.json: field 'version': 2 (this reader knows version 1)"),
            std::string::npos)
      << r.message();
  r = parseTransferFunction("{\"format\":\"paraview\"," + points + "}", "pv.json");
  ASSERT_FALSE(r);
  EXPECT_NE(r.message().find("pv.json: field 'format': \"paraview\""), std::string::npos)
      << r.message();
  EXPECT_TRUE(parseTransferFunction(
      "{\"format\":\"voxlink-transfer-function\",\"version\":1," + points + "}", "ok.json"));
}

// Points that differ past the sixth significant digit were reported as "1000 after 1000".
TEST(TransferFunction, OrderErrorsPrintTheValuesExactly) {
  auto r = parseTransferFunction(R"({"opacity":[[0,0],[1000.0001,0],[1000,1]]})", "tf.json");
  ASSERT_FALSE(r);
  EXPECT_EQ(r.message(),
            "tf.json: field 'opacity[2]': values must not decrease (1000 after 1000.0001)");
  r = parseTransferFunction(
      R"({"opacity":[[0,0],[1,1]],"color":[[0.30000000000000004,0,0,0],[0.3,1,1,1]]})", "tf.json");
  ASSERT_FALSE(r);
  EXPECT_EQ(r.message(),
            "tf.json: field 'color[1]': values must not decrease (0.3 after 0.30000000000000004)");
}

TEST(TransferFunction, JsonRoundTrip) {
  const TransferFunction tf =
      parse(R"({"name":"bone","opacity":[[0,0],[100,0.5]],"color":[[0,1,0,0],[100,0,0,1]]})");
  const TransferFunction back = parse(transferFunctionJson(tf));
  EXPECT_EQ(back.name, "bone");
  ASSERT_EQ(back.opacity.size(), 2u);
  EXPECT_EQ(back.opacity[1].alpha, 0.5);
  EXPECT_EQ(back.color[1].rgb[2], 1.0);
}

}  // namespace
}  // namespace voxlink::tf
