// SPDX-License-Identifier: BSD-3-Clause
// Damaged and hostile inputs: each gives the exact ErrorCode and a message naming the file and
// the field. Every input is made here, in a temp folder (no shared data needed).
#include <gtest/gtest.h>

#include <filesystem>

#include "tests/readers/reader_test_util.h"

namespace voxlink::sources::testing {

namespace {

std::string nrrd(const std::string& fields) { return "NRRD0004\n" + fields + "\n"; }

TEST(BadInput, TruncatedAttachedData) {
  TempDir dir;
  writeWithHeader(dir.file("t.nrrd"),
                  nrrd("type: uint8\ndimension: 3\nsizes: 10 10 10\nencoding: raw\n"),
                  patternBytes(900));
  expectError(openVolume(dir.file("t.nrrd")), ErrorCode::kTruncated,
              {"t.nrrd: data: 10x10x10 u8 needs 1000 bytes", "only 900"});
}

TEST(BadInput, TruncatedSliceFileOfAList) {
  TempDir dir;
  // Three 16x16 i16 slices in numbered files, as vtk_headsq's quarter.%d; the second is cut.
  writeText(dir.file("slices.nhdr"),
            nrrd("type: short\ndimension: 3\nsizes: 16 16 3\nendian: little\nencoding: raw\n"
                 "data file: slice.%d 1 3 1\n"));
  for (int i = 1; i <= 3; ++i)
    writeBytes(dir.file("slice." + std::to_string(i)), patternBytes(i == 2 ? 412 : 512, i));
  expectError(openVolume(dir.file("slices.nhdr")), ErrorCode::kTruncated,
              {"slices.nhdr: data file", "slice.2", "only 412"});
}

TEST(BadInput, DataFilesThatCannotShareTheSlicesEvenlyAreNamed) {
  TempDir dir;
  for (const char* name : {"a.raw", "b.raw"}) writeBytes(dir.file(name), patternBytes(48));
  // Two files for three slices, in each header's list form.
  writeText(dir.file("two.mhd"),
            "NDims = 3\nDimSize = 4 4 3\nElementType = MET_UCHAR\n"
            "ElementDataFile = LIST\na.raw\nb.raw\n");
  expectError(openVolume(dir.file("two.mhd")), ErrorCode::kSizeMismatch,
              {"two.mhd: header field 'ElementDataFile': 2 files cannot each hold whole z slices "
               "of 3"});
  writeText(dir.file("two.nhdr"), nrrd("type: uint8\ndimension: 3\nsizes: 4 4 3\nencoding: raw\n"
                                       "data file: LIST\na.raw\nb.raw"));
  expectError(openVolume(dir.file("two.nhdr")), ErrorCode::kSizeMismatch,
              {"two.nhdr: header field 'data file': 2 files cannot each hold whole z slices of 3"});
  // NRRD's <subdim> 2 means a slice per file: two files for four slices do not fit, though
  // they would split four slices evenly without it.
  writeText(dir.file("subdim.nhdr"), nrrd("type: uint8\ndimension: 3\nsizes: 4 3 4\nencoding: raw\n"
                                          "data file: LIST 2\na.raw\nb.raw"));
  expectError(openVolume(dir.file("subdim.nhdr")), ErrorCode::kSizeMismatch,
              {"subdim.nhdr: header field 'data file': 2 files cannot each hold whole z slices "
               "of 4"});
}

TEST(BadInput, TruncatedGzipStream) {
  TempDir dir;
  auto gz = gzipBytes(patternBytes(20 * 20 * 20));
  gz.resize(gz.size() / 2);
  writeWithHeader(dir.file("cut.nrrd"),
                  nrrd("type: uint8\ndimension: 3\nsizes: 20 20 20\nencoding: gzip\n"), gz);
  expectError(openAndReadAll(dir.file("cut.nrrd")), ErrorCode::kTruncated,
              {"cut.nrrd", "data", "cut off", "of 8000"});
}

TEST(BadInput, RawFileWithWrongDims) {
  TempDir dir;
  writeBytes(dir.file("tooth_13x9x16_uint8.raw"), patternBytes(13 * 9 * 16));
  OpenOptions options;
  options.dims = std::array<uint32_t, 3>{10, 9, 16};
  options.type = ScalarType::kU8;
  expectError(openVolume(dir.file("tooth_13x9x16_uint8.raw"), options), ErrorCode::kSizeMismatch,
              {"tooth_13x9x16_uint8.raw", "10x9x16", "--dims"});
}

TEST(BadInput, HeaderSizesSmallerThanTheData) {
  TempDir dir;
  // Raw: the header claims 60 slices of a 64-slice file.
  writeBytes(dir.file("neghip_16x16x64_uint8.raw"), patternBytes(16 * 16 * 64));
  writeText(dir.file("short.nhdr"),
            nrrd("type: uint8\ndimension: 3\nsizes: 16 16 60\nencoding: raw\ndata file: " +
                 dir.file("neghip_16x16x64_uint8.raw") + "\n"));
  expectError(openVolume(dir.file("short.nhdr")), ErrorCode::kSizeMismatch,
              {"short.nhdr: data file", "neghip_16x16x64_uint8.raw", "header sizes"});
  // Gzip: the stream holds more than the sizes say; found when the last slice is read.
  writeWithHeader(dir.file("long.nrrd"),
                  nrrd("type: uint8\ndimension: 3\nsizes: 8 8 8\nencoding: gzip\n"),
                  gzipBytes(patternBytes(8 * 8 * 9)));
  expectError(openAndReadAll(dir.file("long.nrrd")), ErrorCode::kSizeMismatch,
              {"long.nrrd", "data", "holds 576 bytes, the header describes 512"});
}

TEST(BadInput, UnsupportedTypesEncodingsAndDimensions) {
  TempDir dir;
  const auto write = [&](const std::string& name, const std::string& fields) {
    writeWithHeader(dir.file(name), nrrd(fields), patternBytes(64));
    return dir.file(name);
  };
  expectError(
      openVolume(write("a.nrrd",
                       "type: int64\ndimension: 3\nsizes: 2 2 2\nendian: little\nencoding: raw\n")),
      ErrorCode::kUnsupported, {"a.nrrd", "'type'", "int64"});
  expectError(
      openVolume(write("b.nrrd",
                       "type: block\nblock size: 4\ndimension: 3\nsizes: 2 2 2\nencoding: raw\n")),
      ErrorCode::kUnsupported, {"b.nrrd", "'type'", "block"});
  expectError(
      openVolume(write("c.nrrd", "type: uint8\ndimension: 3\nsizes: 2 2 2\nencoding: bzip2\n")),
      ErrorCode::kUnsupported, {"c.nrrd", "'encoding'", "bzip2"});
  expectError(openVolume(write("d.nrrd", "type: uint8\ndimension: 2\nsizes: 8 8\nencoding: raw\n")),
              ErrorCode::kUnsupported, {"d.nrrd", "'dimension'", "2"});
  expectError(
      openVolume(write("e.nrrd", "type: uint8\ndimension: 4\nsizes: 3 2 2 2\nencoding: raw\n")),
      ErrorCode::kUnsupported, {"e.nrrd", "'dimension'", "first axis of size 3"});
  expectError(
      openVolume(write(
          "f.nrrd",
          "type: uint8\ndimension: 3\nsizes: 2 2 2\nencoding: raw\nspace: 3D-right-handed-time\n")),
      ErrorCode::kUnsupported, {"f.nrrd", "'space'"});
  writeWithHeader(
      dir.file("g.mha"),
      "NDims = 3\nDimSize = 2 2 2\nElementType = MET_LONG_LONG\nElementDataFile = LOCAL\n",
      patternBytes(64));
  expectError(openVolume(dir.file("g.mha")), ErrorCode::kUnsupported,
              {"g.mha", "'ElementType'", "MET_LONG_LONG"});
  writeWithHeader(dir.file("h.mha"),
                  "NDims = 3\nDimSize = 2 2 2\nElementNumberOfChannels = 3\nElementType = "
                  "MET_UCHAR\nElementDataFile = LOCAL\n",
                  patternBytes(24));
  expectError(openVolume(dir.file("h.mha")), ErrorCode::kUnsupported,
              {"h.mha", "'ElementNumberOfChannels'", "3"});
}

TEST(BadInput, MalformedHeaderFields) {
  TempDir dir;
  const auto write = [&](const std::string& name, const std::string& fields) {
    writeWithHeader(dir.file(name), nrrd(fields), patternBytes(64));
    return dir.file(name);
  };
  expectError(
      openVolume(write("foot.nrrd", "type: uint8\ndimension: 3\nsizes: 256 256\nencoding: raw\n")),
      ErrorCode::kCorrupt,
      {"foot.nrrd: header field 'sizes': expected 3 positive integers", "got '256 256'"});
  expectError(
      openVolume(
          write("u.nrrd", "type: uint8\ndimension: 3\nsizes: 2 2 2\nencoding: raw\ncolour: red\n")),
      ErrorCode::kUnsupported, {"u.nrrd", "unknown header field 'colour'"});
  expectError(
      openVolume(
          write("t.nrrd", "type: uint8\ntype: uint8\ndimension: 3\nsizes: 2 2 2\nencoding: raw\n")),
      ErrorCode::kCorrupt, {"t.nrrd", "'type' given twice"});
  expectError(
      openVolume(write("e.nrrd", "type: short\ndimension: 3\nsizes: 2 2 2\nencoding: raw\n")),
      ErrorCode::kCorrupt, {"e.nrrd", "'endian' missing"});
  expectError(
      openVolume(write(
          "s.nrrd", "type: uint8\ndimension: 3\nsizes: 2 2 2\nspacings: 1 0 1\nencoding: raw\n")),
      ErrorCode::kCorrupt, {"s.nrrd", "'spacings'", "axis 1"});
  expectError(
      openVolume(write("n.nrrd", "type: uint8\ndimension: 3\nsizes: 2 x 2\nencoding: raw\n")),
      ErrorCode::kCorrupt, {"n.nrrd", "'sizes'", "2 x 2"});
  writeBytes(dir.file("m.nrrd"), patternBytes(100));
  expectError(openVolume(dir.file("m.nrrd")), ErrorCode::kCorrupt, {"m.nrrd", "not a NRRD file"});
  writeText(dir.file("p.nhdr"),
            nrrd("type: uint8\ndimension: 3\nsizes: 2 2 2\nencoding: raw\ndata file: x%s 1 2 1\n"));
  expectError(openVolume(dir.file("p.nhdr")), ErrorCode::kCorrupt,
              {"p.nhdr", "'data file'", "x%s"});
}

TEST(BadInput, HostileSizesFailBeforeAllocating) {
  TempDir dir;
  writeWithHeader(dir.file("huge.nrrd"),
                  nrrd("type: uint8\ndimension: 3\nsizes: 100000 100000 100000\nencoding: gzip\n"),
                  gzipBytes(patternBytes(10)));
  expectError(openVolume(dir.file("huge.nrrd")), ErrorCode::kTooLarge, {"huge.nrrd", "'sizes'"});
  writeWithHeader(
      dir.file("big.mha"),
      "NDims = 3\nDimSize = 5000000000 2 2\nElementType = MET_UCHAR\nElementDataFile = LOCAL\n",
      patternBytes(10));
  expectError(openVolume(dir.file("big.mha")), ErrorCode::kTooLarge, {"big.mha", "'DimSize'"});
}

TEST(BadInput, CorruptGzipStream) {
  TempDir dir;
  // A detached gzip data file (as vtk.js exports, e.g. LIDC2) damaged in the middle.
  const std::string gz = "b1ad142a1ebc80f957fcdc329e876d51.gz";
  writeText(dir.file("LIDC2.nhdr"),
            nrrd("type: short\ndimension: 3\nsizes: 32 32 32\nendian: little\nencoding: gzip\n"
                 "data file: " +
                 gz + "\n"));
  auto bytes = gzipBytes(patternBytes(32 * 32 * 32 * 2));
  for (size_t i = bytes.size() / 2; i < bytes.size() / 2 + 64; ++i) bytes[i] ^= 0x5a;
  writeBytes(dir.file(gz), bytes);
  expectError(openAndReadAll(dir.file("LIDC2.nhdr")), ErrorCode::kCorrupt,
              {"LIDC2.nhdr: data file", gz, "corrupt"});
}

TEST(BadInput, CorruptZlibMetaImage) {
  TempDir dir;
  auto z = gzipBytes(patternBytes(16 * 16 * 16), false);
  for (size_t i = 20; i < 40; ++i) z[i] ^= 0xff;
  writeWithHeader(dir.file("z.mha"),
                  "NDims = 3\nDimSize = 16 16 16\nElementType = MET_UCHAR\nCompressedData = "
                  "True\nElementDataFile = LOCAL\n",
                  z);
  expectError(openAndReadAll(dir.file("z.mha")), ErrorCode::kCorrupt,
              {"z.mha", "ElementDataFile", "corrupt"});
}

TEST(BadInput, MissingDetachedDataFile) {
  TempDir dir;
  writeText(dir.file("gone.nhdr"),
            nrrd("type: uint8\ndimension: 3\nsizes: 2 2 2\nencoding: raw\ndata file: gone.raw\n"));
  expectError(openVolume(dir.file("gone.nhdr")), ErrorCode::kIo,
              {"gone.nhdr: data file", "gone.raw does not exist"});
  writeText(dir.file("gone.mhd"),
            "NDims = 3\nDimSize = 2 2 2\nElementType = MET_UCHAR\nElementDataFile = gone.zraw\n");
  expectError(openVolume(dir.file("gone.mhd")), ErrorCode::kIo,
              {"gone.mhd", "ElementDataFile", "gone.zraw does not exist"});
}

TEST(BadInput, OptionsThatDisagreeWithTheHeader) {
  TempDir dir;
  const std::string header = dir.file("quarter.nhdr");
  writeText(header, nrrd("type: short\ndimension: 3\nsizes: 8 8 9\nendian: little\n"
                         "encoding: raw\ndata file: quarter.raw\n"));
  writeBytes(dir.file("quarter.raw"), patternBytes(8 * 8 * 9 * 2));
  OpenOptions dims;
  dims.dims = std::array<uint32_t, 3>{8, 8, 7};
  expectError(openVolume(header, dims), ErrorCode::kInvalidArgument,
              {"quarter.nhdr", "--dims 8,8,7", "8x8x9"});
  OpenOptions type;
  type.type = ScalarType::kU16;
  expectError(openVolume(header, type), ErrorCode::kInvalidArgument,
              {"quarter.nhdr", "--type u16", "i16"});
  OpenOptions spacing;
  spacing.spacing = std::array<double, 3>{1, 2, 3};
  auto source = openOrDie(header, spacing);
  ASSERT_TRUE(source);
  EXPECT_EQ(source->info().spacing, (std::array<double, 3>{1, 2, 3}));
  EXPECT_TRUE(hasNote(source->info(), "--spacing")) << notesOf(source->info());
}

}  // namespace
}  // namespace voxlink::sources::testing
