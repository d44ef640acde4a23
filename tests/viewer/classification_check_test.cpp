// SPDX-License-Identifier: BSD-3-Clause
// The viewer's classification check: which values a TF asks for that a file's classification
// removed.
#include "viewer/app/detail/classification_check.h"

#include <gtest/gtest.h>

#include <cmath>

namespace voxlink::viewer {
namespace {

TEST(ClassificationCheck, TfOpacityOnRemovedValuesIsFound) {
  FileClassification c;
  c.recorded = true;
  c.keep = {{60, HUGE_VAL, false, true}};  // --threshold 60
  tf::TransferFunction tf;
  tf.opacity = {{70, 0.0}, {90, 0.5}};
  EXPECT_TRUE(visibleButRemoved(tf, c).empty());
  tf.opacity = {{40, 0.0}, {90, 0.5}};  // opacity from just above 40
  const auto bad = visibleButRemoved(tf, c);
  ASSERT_EQ(bad.size(), 1u);
  EXPECT_EQ(bad[0].lo, 40);
  EXPECT_TRUE(bad[0].loOpen);
  EXPECT_EQ(bad[0].hi, 60);
  EXPECT_TRUE(bad[0].hiOpen);
}

}  // namespace
}  // namespace voxlink::viewer
