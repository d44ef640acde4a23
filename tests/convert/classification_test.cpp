// SPDX-License-Identifier: BSD-3-Clause
#include "convert/classification.h"

#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

namespace voxlink::convert {
namespace {

TEST(Classification, ThresholdSpecs) {
  auto c = thresholdClassification({"60"});
  ASSERT_TRUE(c);
  EXPECT_FALSE(c->keeps(59.999));
  EXPECT_TRUE(c->keeps(60));
  EXPECT_TRUE(c->keeps(1e30));
  c = thresholdClassification({"10,20", "30, 40"});
  ASSERT_TRUE(c) << c.message();
  EXPECT_TRUE(c->keeps(20));
  EXPECT_FALSE(c->keeps(25));
  EXPECT_TRUE(c->keeps(30));
  EXPECT_EQ(thresholdClassification({"x"}).code(), ErrorCode::kInvalidArgument);
  EXPECT_NE(thresholdClassification({"5,1"}).message().find("below lower bound"),
            std::string::npos);
}

TEST(Classification, KeepOutsideThePaperConfidenceInterval) {
  // Paper, section 6.2: keep N(0,1) values outside the 95 % interval.
  auto c = keepOutsideClassification(-1.96, 1.96, std::nullopt, std::nullopt);
  ASSERT_TRUE(c);
  EXPECT_TRUE(c->keeps(-2.0));
  EXPECT_FALSE(c->keeps(-1.96));
  EXPECT_FALSE(c->keeps(0.0));
  EXPECT_TRUE(c->keeps(1.97));
  auto standardized = keepOutsideClassification(-1.96, 1.96, 10.0, 2.0);
  ASSERT_TRUE(standardized);
  EXPECT_TRUE(standardized->keeps(14.0));   // z = 2
  EXPECT_FALSE(standardized->keeps(13.0));  // z = 1.5
  EXPECT_FALSE(keepOutsideClassification(1, -1, std::nullopt, std::nullopt));
  EXPECT_FALSE(keepOutsideClassification(-1, 1, 0.0, 0.0));
}

TEST(Classification, JsonRoundTripKeepsInfinities) {
  for (const Classification& c :
       {*thresholdClassification({"60"}), *keepOutsideClassification(-1.96, 1.96, 0.5, 2.0)}) {
    auto back = classificationFromJson(classificationToJson(c));
    ASSERT_TRUE(back) << back.message();
    EXPECT_EQ(back->kind, c.kind);
    ASSERT_EQ(back->keep.size(), c.keep.size());
    for (size_t i = 0; i < c.keep.size(); ++i) {
      EXPECT_EQ(back->keep[i].lo, c.keep[i].lo);
      EXPECT_EQ(back->keep[i].hi, c.keep[i].hi);
      EXPECT_EQ(back->keep[i].loOpen, c.keep[i].loOpen);
    }
    EXPECT_EQ(back->mean, c.mean);
    EXPECT_EQ(back->sigma, c.sigma);
  }
  EXPECT_EQ(classificationToJson(*thresholdClassification({"60"}))["keep"][0]["hi"], "inf");
}

}  // namespace
}  // namespace voxlink::convert
