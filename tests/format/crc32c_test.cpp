// SPDX-License-Identifier: BSD-3-Clause
#include "base/crc32c.h"

#include <gtest/gtest.h>

#include <random>
#include <string>
#include <vector>

namespace voxlink {
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

// Ranks checksum their parts of a section; the writer joins them (format/file_writer.cpp).
TEST(Crc32c, CombineEqualsChecksumOfTheJoinedBytes) {
  std::vector<uint8_t> bytes(100000);
  for (size_t i = 0; i < bytes.size(); ++i) bytes[i] = static_cast<uint8_t>(i * 2654435761u >> 13);
  const uint32_t whole = crc32c(bytes.data(), bytes.size());
  for (size_t cut : {size_t{0}, size_t{1}, size_t{7}, size_t{4096}, size_t{65537}, bytes.size()}) {
    const uint32_t a = crc32c(bytes.data(), cut);
    const uint32_t b = crc32c(bytes.data() + cut, bytes.size() - cut);
    EXPECT_EQ(crc32cCombine(a, b, bytes.size() - cut), whole) << "cut at " << cut;
  }
  // Three parts joined left to right.
  const uint32_t p0 = crc32c(bytes.data(), 1000), p1 = crc32c(bytes.data() + 1000, 30000),
                 p2 = crc32c(bytes.data() + 31000, bytes.size() - 31000);
  EXPECT_EQ(crc32cCombine(crc32cCombine(p0, p1, 30000), p2, bytes.size() - 31000), whole);
}

}  // namespace
}  // namespace voxlink
