// SPDX-License-Identifier: BSD-3-Clause
// The output is byte-identical for any slab size, thread count and access path.
#include <gtest/gtest.h>

#include "convert/converter.h"
#include "tests/convert/volume_fixtures.h"
#include "tests/support/test_util.h"

namespace voxlink::convert {
namespace {

TEST(ConverterDeterminism, SlabSizeThreadsAndStreamingDoNotChangeABit) {
  testing::TempDir dir;
  std::vector<uint8_t> reference;
  int runs = 0;
  for (bool sequential : {false, true}) {
    auto ball = testing::makeBall({70, 53, 61}, sequential);
    for (uint32_t slab : {1u, 8u, 24u, 64u, 1000u}) {
      for (unsigned threads : {1u, 2u, 3u}) {
        ConvertOptions o;
        o.classification = *thresholdClassification({"60"});
        o.slabSlices = slab;
        o.threads = threads;
        // (built with append: g++ 12 gives a false -Wrestrict on "d" + std::to_string(...))
        std::string name = "run";
        name.append(std::to_string(runs++)).append(".vxl");
        const std::string path = dir.file(name);
        auto s = convertVolume(*ball, o, path);
        ASSERT_TRUE(s) << s.message();
        auto bytes = testing::readBytes(path);
        if (reference.empty()) reference = bytes;
        EXPECT_EQ(bytes, reference)
            << "slab " << slab << " threads " << threads << " sequential " << sequential;
      }
    }
  }
}

}  // namespace
}  // namespace voxlink::convert
