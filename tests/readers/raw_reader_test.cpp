// SPDX-License-Identifier: BSD-3-Clause
// Headerless raw volumes: the bytes come back as the file holds them, mapped in place.
#include <gtest/gtest.h>

#include <cstring>

#include "tests/readers/reader_test_util.h"

namespace voxlink::sources::testing {

namespace {

OpenOptions rawOptions(uint32_t x, uint32_t y, uint32_t z, ScalarType type) {
  OpenOptions o;
  o.dims = std::array<uint32_t, 3>{x, y, z};
  o.type = type;
  return o;
}

TEST(RawReader, NeghipAndToothAreTheirFilesMappedInPlace) {
  VOXLINK_REQUIRE_DATA("volume/neghip_64x64x64_uint8.raw");
  VOXLINK_REQUIRE_DATA("ct/tooth_103x94x161_uint8.raw");
  const struct {
    const char* path;
    std::array<uint32_t, 3> dims;
  } cases[] = {{"volume/neghip_64x64x64_uint8.raw", {64, 64, 64}},
               {"ct/tooth_103x94x161_uint8.raw", {103, 94, 161}}};
  for (const auto& c : cases) {
    SCOPED_TRACE(c.path);
    auto source =
        openOrDie(dataPath(c.path), rawOptions(c.dims[0], c.dims[1], c.dims[2], ScalarType::kU8));
    ASSERT_TRUE(source);
    EXPECT_EQ(source->info().format, "raw");
    EXPECT_EQ(source->info().dims, c.dims);
    const auto bytes = readBytes(dataPath(c.path));
    auto data = readAll(*source);
    ASSERT_TRUE(data) << data.message();
    EXPECT_TRUE(*data == bytes);
    const void* mapped = source->map(1, 2);
    ASSERT_NE(mapped, nullptr);
    EXPECT_EQ(std::memcmp(mapped, bytes.data() + source->info().sliceBytes(),
                          2 * source->info().sliceBytes()),
              0);
  }
}

TEST(RawReader, WrongTypeAndMissingOptions) {
  VOXLINK_REQUIRE_DATA("volume/neghip_64x64x64_uint8.raw");
  const std::string path = dataPath("volume/neghip_64x64x64_uint8.raw");
  expectError(openVolume(path, rawOptions(64, 64, 64, ScalarType::kU16)), ErrorCode::kTruncated,
              {"neghip_64x64x64_uint8.raw", "64x64x64 u16", "needs 524288 bytes"});
  expectError(openVolume(path), ErrorCode::kInvalidArgument,
              {"neghip_64x64x64_uint8.raw", "--dims"});
}

}  // namespace
}  // namespace voxlink::sources::testing
