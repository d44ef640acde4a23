// SPDX-License-Identifier: BSD-3-Clause
// The small shared pieces: number lists, file lists, natural order, axis notes, rescale types,
// the gzip stream across concatenated members.
#include <gtest/gtest.h>

#include <algorithm>

#include "sources/readers/detail/axes.h"
#include "sources/readers/detail/file_list.h"
#include "sources/readers/detail/inflate_stream.h"
#include "sources/readers/detail/rescale.h"
#include "sources/readers/detail/text_header.h"
#include "tests/readers/reader_test_util.h"

namespace voxlink::sources::testing {

namespace {

TEST(HeaderHelpers, NumberListsNameFileAndField) {
  auto ok = parseDoubles(" 1.5  -2e3 +4 nan", "f.nrrd", "spacings");
  ASSERT_TRUE(ok);
  EXPECT_EQ((*ok)[1], -2000);
  EXPECT_EQ((*ok)[2], 4);
  expectError(parseDoubles("1 2", "f.nrrd", "spacings", 3), ErrorCode::kCorrupt,
              {"f.nrrd: header field 'spacings': expected 3 numbers, got '1 2'"});
  expectError(parseIntegers("1 2.5 3", "f.nrrd", "sizes"), ErrorCode::kCorrupt,
              {"'sizes'", "integers", "1 2.5 3"});
  expectError(parseBool("yes", "f.mhd", "CompressedData"), ErrorCode::kCorrupt,
              {"'CompressedData'", "True or False"});
}

TEST(HeaderHelpers, NumberedFileLists) {
  auto names = expandNumberedFiles({"slice%03d.raw", "8", "12", "2"}, "h.nhdr", "data file");
  ASSERT_TRUE(names) << names.message();
  EXPECT_EQ(*names, (std::vector<std::string>{"slice008.raw", "slice010.raw", "slice012.raw"}));
  auto down = expandNumberedFiles({"q.%d", "3", "1", "-1"}, "h.nhdr", "data file");
  ASSERT_TRUE(down);
  EXPECT_EQ(*down, (std::vector<std::string>{"q.3", "q.2", "q.1"}));
  auto percent = expandNumberedFiles({"100%%_%2d", "1", "1", "1"}, "h.nhdr", "data file");
  ASSERT_TRUE(percent);
  EXPECT_EQ(percent->front(), "100%_ 1");
  for (const char* bad : {"x%s", "x%d%d", "plain", "x%n"})
    expectError(expandNumberedFiles({bad, "1", "2", "1"}, "h.nhdr", "data file"),
                ErrorCode::kCorrupt, {"h.nhdr", "'data file'", bad});
  expectError(expandNumberedFiles({"q.%d", "1", "5", "-1"}, "h.nhdr", "data file"),
              ErrorCode::kCorrupt, {"step"});
  expectError(expandNumberedFiles({"q.%d", "1", "99999999", "1"}, "h.nhdr", "data file"),
              ErrorCode::kTooLarge, {"files listed"});
}

TEST(HeaderHelpers, NaturalOrder) {
  std::vector<std::string> names = {"s10.png", "s2.png",  "s1.png",  "s02.png",
                                    "a.png",   "s1b.png", "s100.png"};
  std::sort(names.begin(), names.end(),
            [](const auto& a, const auto& b) { return naturalLess(a, b); });
  EXPECT_EQ(names, (std::vector<std::string>{"a.png", "s1.png", "s1b.png", "s2.png", "s02.png",
                                             "s10.png", "s100.png"}));
  EXPECT_FALSE(naturalLess("x", "x"));
}

TEST(HeaderHelpers, AxisNotes) {
  EXPECT_TRUE(summarizeAxes({Vec3{2, 0, 0}, Vec3{0, 3, 0}, Vec3{0, 0, 4}}, "dirs").note.empty());
  const AxesSummary flipped = summarizeAxes({Vec3{-2, 0, 0}, Vec3{0, 3, 0}, Vec3{0, 0, 4}}, "dirs");
  EXPECT_EQ(flipped.lengths, (Vec3{2, 3, 4}));
  EXPECT_NE(flipped.note.find("-x +y +z"), std::string::npos) << flipped.note;
  const AxesSummary permuted = summarizeAxes({Vec3{0, 1, 0}, Vec3{1, 0, 0}, Vec3{0, 0, 1}}, "dirs");
  EXPECT_NE(permuted.note.find("+y +x +z"), std::string::npos) << permuted.note;
  const AxesSummary oblique =
      summarizeAxes({Vec3{0.6, 0.8, 0}, Vec3{-0.8, 0.6, 0}, Vec3{0, 0, 1}}, "dirs");
  EXPECT_NEAR(oblique.lengths[0], 1.0, 1e-15);
  EXPECT_NE(oblique.note.find("oblique"), std::string::npos) << oblique.note;
}

TEST(HeaderHelpers, RescaledTypes) {
  EXPECT_EQ(rescaledType(ScalarType::kU8, 0, 255, 1, 0), ScalarType::kU8);
  EXPECT_EQ(rescaledType(ScalarType::kU8, 0, 255, 1, -128), ScalarType::kI8);
  EXPECT_EQ(rescaledType(ScalarType::kU16, 0, 4095, 1, -1024), ScalarType::kI16);
  EXPECT_EQ(rescaledType(ScalarType::kU16, 0, 65535, 1, -1024), ScalarType::kI32);
  EXPECT_EQ(rescaledType(ScalarType::kI16, -32768, 32767, 0.5, 0), ScalarType::kF32);
  EXPECT_EQ(rescaledType(ScalarType::kI32, -2147483648.0, 2147483647.0, 0.5, 0), ScalarType::kF64);
  EXPECT_EQ(rescaledType(ScalarType::kU32, 0, 4294967295.0, 2, 0), ScalarType::kF64);  // beyond i32
  EXPECT_EQ(rescaledType(ScalarType::kF32, -1, 1, 2, 0), ScalarType::kF32);
  const int16_t in[3] = {-3, 0, 1000};
  int32_t out[3];
  convertRescaled(in, ScalarType::kI16, out, ScalarType::kI32, 3, 3, -1024);
  EXPECT_EQ(out[0], -1033);
  EXPECT_EQ(out[2], 1976);
}

TEST(HeaderHelpers, GzipMembersConcatenateAndSkipWorks) {
  TempDir dir;
  const auto a = patternBytes(70000, 1), b = patternBytes(50000, 2);
  auto file = gzipBytes(a);
  const auto second = gzipBytes(b);
  file.insert(file.end(), second.begin(), second.end());
  writeBytes(dir.file("two.gz"), file);
  auto stream = InflateStream::open(dir.file("two.gz"), 0, "two.gz");
  ASSERT_TRUE(stream) << stream.message();
  std::vector<uint8_t> got(a.size() + b.size());
  ASSERT_TRUE((*stream)->read(got.data(), got.size()).isOk());
  EXPECT_TRUE(std::equal(a.begin(), a.end(), got.begin()));
  EXPECT_TRUE(std::equal(b.begin(), b.end(), got.begin() + static_cast<long>(a.size())));
  EXPECT_TRUE((*stream)->expectEnd().isOk());
  ASSERT_TRUE((*stream)->rewind().isOk());
  ASSERT_TRUE((*stream)->skip(69999).isOk());
  uint8_t two[2];
  ASSERT_TRUE((*stream)->read(two, 2).isOk());
  EXPECT_EQ(two[0], a.back());
  EXPECT_EQ(two[1], b.front());
  expectError((*stream)->read(got.data(), got.size()), ErrorCode::kTruncated,
              {"two.gz", "ends after 120000"});
}

}  // namespace
}  // namespace voxlink::sources::testing
