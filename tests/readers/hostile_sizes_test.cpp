// SPDX-License-Identifier: BSD-3-Clause
// Sizes from files and options that overflow 64-bit arithmetic or exceed base/limits.h: each
// must fail with a one-line error before anything is allocated or written. Synthetic files only.
#include <gtest/gtest.h>
#include <zlib.h>

#include <cstring>

#include "sources/readers/detail/file_list.h"
#include "tests/readers/npy_test_util.h"
#include "tests/readers/reader_test_util.h"

namespace voxlink::sources::testing {

namespace {

void appendU64(std::vector<uint8_t>& out, uint64_t v) {
  for (int i = 0; i < 8; ++i) out.push_back(static_cast<uint8_t>(v >> (8 * i)));
}

// An appended-raw, zlib-compressed, UInt64-header VTK image of `extent` u8 whose data is
// `payload` (the block header and whatever follows it).
std::vector<uint8_t> vtiWithPayload(const std::string& extent,
                                    const std::vector<uint8_t>& payload) {
  const std::string head =
      "<?xml version=\"1.0\"?>\n<VTKFile type=\"ImageData\" byte_order=\"LittleEndian\" "
      "header_type=\"UInt64\" compressor=\"vtkZLibDataCompressor\">\n<ImageData WholeExtent=\"" +
      extent + "\">\n<Piece Extent=\"" + extent +
      "\"><PointData><DataArray type=\"UInt8\" Name=\"v\" format=\"appended\" offset=\"0\"/>"
      "</PointData></Piece></ImageData>\n<AppendedData encoding=\"raw\">\n   _";
  std::vector<uint8_t> file(head.begin(), head.end());
  file.insert(file.end(), payload.begin(), payload.end());
  const std::string tail = "\n</AppendedData>\n</VTKFile>\n";
  file.insert(file.end(), tail.begin(), tail.end());
  return file;
}

TEST(HostileSizes, VtiBlockSizesThatWrapAroundFailBeforeDecoding) {
  TempDir dir;
  // 512 bytes wanted; two blocks of 2^63 + 256 wrap to 512 in unchecked 64-bit arithmetic and
  // used to decompress past the 512-byte buffer.
  std::vector<uint8_t> wrap;
  const uint64_t half = (uint64_t{1} << 63) + 256;
  for (uint64_t v : {uint64_t{2}, half, half, uint64_t{16}, uint64_t{16}}) appendU64(wrap, v);
  wrap.resize(wrap.size() + 2048, 0x78);
  writeBytes(dir.file("wrap.vti"), vtiWithPayload("0 511 0 0 0 0", wrap));
  expectError(openVolume(dir.file("wrap.vti")), ErrorCode::kSizeMismatch,
              {"wrap.vti", "DataArray", "do not make the 512 bytes"});

  // Compressed block sizes whose sum wraps around to a few bytes.
  std::vector<uint8_t> sum;
  for (uint64_t v : {uint64_t{2}, uint64_t{256}, uint64_t{0}, ~uint64_t{0}, uint64_t{2}})
    appendU64(sum, v);
  sum.resize(sum.size() + 64, 0);
  writeBytes(dir.file("sum.vti"), vtiWithPayload("0 511 0 0 0 0", sum));
  expectError(openVolume(dir.file("sum.vti")), ErrorCode::kCorrupt, {"sum.vti", "block"});

  // A block of 1 compressed byte cannot inflate to 512 (zlib expands at most ~1032:1).
  std::vector<uint8_t> tiny;
  for (uint64_t v : {uint64_t{1}, uint64_t{512}, uint64_t{0}, uint64_t{0}}) appendU64(tiny, v);
  writeBytes(dir.file("tiny.vti"), vtiWithPayload("0 511 0 0 0 0", tiny));
  expectError(openVolume(dir.file("tiny.vti")), ErrorCode::kCorrupt,
              {"tiny.vti", "block 0 of 0 bytes"});
}

TEST(HostileSizes, VtiSmallArrayWithVtksDefaultBlockSizeStillOpens) {
  // VTK writes block size 32768 even for an array of 120 bytes: one block, last size 120.
  TempDir dir;
  const auto values = patternBytes(120, 9);
  std::vector<uint8_t> z(compressBound(values.size()));
  uLongf zn = z.size();
  ASSERT_EQ(compress(z.data(), &zn, values.data(), values.size()), Z_OK);
  std::vector<uint8_t> payload;
  for (uint64_t v : {uint64_t{1}, uint64_t{32768}, uint64_t{120}, uint64_t{zn}})
    appendU64(payload, v);
  payload.insert(payload.end(), z.begin(), z.begin() + static_cast<long>(zn));
  writeBytes(dir.file("small.vti"), vtiWithPayload("0 5 0 4 0 3", payload));
  auto source = openOrDie(dir.file("small.vti"));
  ASSERT_TRUE(source);
  auto data = readAll(*source);
  ASSERT_TRUE(data) << data.message();
  EXPECT_TRUE(*data == values);
}

TEST(HostileSizes, VtiHugeExtentFailsOnTheMissingDataNotOnAllocation) {
  TempDir dir;
  // 2^40 voxels (within the limits) announced by a 1 KB file: the block table is missing, so
  // the read stops there; it must not try to allocate the terabyte first.
  std::vector<uint8_t> header;
  for (uint64_t v : {uint64_t{1} << 24, uint64_t{1} << 16, uint64_t{0}}) appendU64(header, v);
  writeBytes(dir.file("huge.vti"), vtiWithPayload("0 65535 0 65535 0 255", header));
  expectError(openVolume(dir.file("huge.vti")), ErrorCode::kTruncated, {"huge.vti", "ends early"});
  // An axis beyond the per-axis limit fails on the extent itself.
  writeBytes(dir.file("long.vti"), vtiWithPayload("0 1048575 0 1048575 0 0", header));
  expectError(openVolume(dir.file("long.vti")), ErrorCode::kTooLarge,
              {"long.vti", "'WholeExtent'", "1048576"});
}

TEST(HostileSizes, NumberedFileListsWithExtremeBounds) {
  const std::string min = "-9223372036854775808", max = "9223372036854775807";
  // (last - first) overflowed int64, and INT64_MIN / -1 trapped (SIGFPE).
  expectError(expandNumberedFiles({"s%d.raw", min, max, "1"}, "h.nhdr", "data file"),
              ErrorCode::kTooLarge, {"h.nhdr", "'data file'", "files listed"});
  expectError(expandNumberedFiles({"s%d.raw", "0", min, "-1"}, "h.nhdr", "data file"),
              ErrorCode::kTooLarge, {"h.nhdr", "'data file'", "files listed"});
  expectError(expandNumberedFiles({"s%d.raw", max, min, "-1"}, "h.mhd", "ElementDataFile"),
              ErrorCode::kTooLarge, {"h.mhd", "'ElementDataFile'"});
  // The extremes themselves are fine as single entries, and print without overflow.
  auto one = expandNumberedFiles({"s%d.raw", min, min, "-1"}, "h.nhdr", "data file");
  ASSERT_TRUE(one) << one.message();
  EXPECT_EQ(one->front(), "s" + min + ".raw");
  auto last = expandNumberedFiles({"s%d.raw", max, max, min}, "h.nhdr", "data file");
  ASSERT_TRUE(last) << last.message();
  EXPECT_EQ(last->front(), "s" + max + ".raw");
}

TEST(HostileSizes, RawDimsThatWrapToZeroBytes) {
  TempDir dir;
  writeBytes(dir.file("empty.raw"), {});
  // 2^22 * 2^21 * 2^21 f64 values are 2^67 bytes: 0 modulo 2^64.
  OpenOptions o;
  o.dims = std::array<uint32_t, 3>{4194304, 2097152, 2097152};
  o.type = ScalarType::kF64;
  expectError(openVolume(dir.file("empty.raw"), o), ErrorCode::kInvalidArgument,
              {"empty.raw", "'--dims'", "4194304"});
  o.dims = std::array<uint32_t, 3>{65536, 65536, 65536};
  expectError(openVolume(dir.file("empty.raw"), o), ErrorCode::kInvalidArgument,
              {"empty.raw", "'--dims'", "voxels"});
}

TEST(HostileSizes, NpyShapeThatWrapsToZeroBytes) {
  TempDir dir;
  writeBytes(
      dir.file("wrap.npy"),
      voxlink::testing::npyBytes(
          1, "{'descr': '<f8', 'fortran_order': False, 'shape': (2097152, 2097152, 4194304), }",
          {}));
  expectError(openVolume(dir.file("wrap.npy")), ErrorCode::kTooLarge,
              {"wrap.npy", "'shape'", "4194304"});
  writeBytes(
      dir.file("big.npy"),
      voxlink::testing::npyBytes(
          1, "{'descr': '|u1', 'fortran_order': False, 'shape': (65536, 65536, 65536), }", {}));
  expectError(openVolume(dir.file("big.npy")), ErrorCode::kTooLarge, {"big.npy", "voxels"});
}

TEST(HostileSizes, GslibTitleThatWrapsToZeroRows) {
  TempDir dir;
  writeText(dir.file("wrap.dat"), "4194304 2097152 2097152\n1\nvalue\n");
  OpenOptions o;
  o.format = "gslib";
  expectError(openVolume(dir.file("wrap.dat"), o), ErrorCode::kCorrupt,
              {"wrap.dat", "'title'", "4194304"});
}

}  // namespace
}  // namespace voxlink::sources::testing
