#include "format/crc32c.h"

#include <gtest/gtest.h>

#include <random>
#include <string>
#include <vector>

namespace voxlink::format {
namespace {

TEST(Crc32c, KnownVectors) {
  // RFC 3720 (iSCSI) test vectors.
  EXPECT_EQ(crc32c("123456789", 9), 0xE3069283u);
  std::vector<uint8_t> zeros(32, 0), ones(32, 0xFF);
  EXPECT_EQ(crc32c(zeros.data(), zeros.size()), 0x8A9136AAu);
  EXPECT_EQ(crc32c(ones.data(), ones.size()), 0x62A8AB43u);
  EXPECT_EQ(crc32c(nullptr, 0), 0u);
}

TEST(Crc32c, HardwareAndPortableAgreeAndChain) {
  std::mt19937 rng(3);
  std::vector<uint8_t> data(100003);
  for (auto& b : data) b = static_cast<uint8_t>(rng());
  // Sizes around the three-stream blocks of the hardware path (3 x 4096 bytes).
  for (size_t size :
       {0u, 1u, 7u, 8u, 9u, 63u, 1000u, 12287u, 12288u, 12289u, 24576u, 24583u, 100003u}) {
    EXPECT_EQ(crc32c(data.data(), size), crc32cPortable(data.data(), size)) << size;
  }
  const uint32_t whole = crc32c(data.data(), data.size());
  const uint32_t first = crc32c(data.data(), 5001);
  EXPECT_EQ(crc32c(data.data() + 5001, data.size() - 5001, first), whole);
  for (size_t offset : {1u, 3u, 4097u}) {  // unaligned starts, chained from a non-zero crc
    const uint32_t head = crc32cPortable(data.data(), offset);
    EXPECT_EQ(crc32c(data.data() + offset, 50000, head),
              crc32cPortable(data.data() + offset, 50000, head))
        << offset;
  }
}

}  // namespace
}  // namespace voxlink::format
