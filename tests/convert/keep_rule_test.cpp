// SPDX-License-Identifier: BSD-3-Clause
// The converter's fast keep rules agree with Classification::keeps() on every value.
#include "convert/detail/keep_rule.h"

#include <gtest/gtest.h>

namespace voxlink::convert {
namespace {

std::vector<Classification> classifications() {
  std::vector<Classification> cs;
  cs.push_back(*thresholdClassification({"60"}));
  cs.push_back(*thresholdClassification({"59.5"}));
  cs.push_back(*thresholdClassification({"-20,-3.5", "100,100", "30000,70000"}));
  cs.push_back(*keepOutsideClassification(-1.96, 1.96, std::nullopt, std::nullopt));
  cs.push_back(*keepOutsideClassification(-1.96, 1.96, 100.0, 15.0));
  auto tf = tf::parseTransferFunction(
      R"({"opacity":[[0,0],[60,0],[61,0.5],[90,0],[90,1],[120,0]]})", "tf");
  cs.push_back(tfClassification(*tf));
  cs.push_back(keepAllClassification());
  return cs;
}

template <class T>
void checkType() {
  for (const Classification& c : classifications()) {
    const auto table = keepTable<T>(c);
    const TableKeep<T> tableKeep{table.data()};
    T lo = 0, hi = 0;
    const bool single = c.kind != Classification::Kind::kAll && !c.mean && c.keep.size() == 1;
    const bool any = single && integerRange<T>(c.keep[0], lo, hi);
    for (int32_t v = std::numeric_limits<T>::min(); v <= std::numeric_limits<T>::max(); ++v) {
      const bool expected = c.keeps(v);
      ASSERT_EQ(tableKeep(static_cast<T>(v)), expected) << c.describe() << " v=" << v;
      ASSERT_EQ(GeneralKeep<T>{&c}(static_cast<T>(v)), expected);
      if (single) {
        const RangeKeep<T> range{lo, hi};
        ASSERT_EQ(any && range(static_cast<T>(v)), expected) << c.describe() << " v=" << v;
      }
    }
  }
}

TEST(KeepRule, FastFormsAgreeWithClassificationOnEveryValue) {
  checkType<uint8_t>();
  checkType<int8_t>();
  checkType<uint16_t>();
  checkType<int16_t>();
}

}  // namespace
}  // namespace voxlink::convert
