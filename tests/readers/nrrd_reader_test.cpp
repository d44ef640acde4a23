// SPDX-License-Identifier: BSD-3-Clause
// NRRD on the real files: every value checked against an independent decoding of the same
// bytes (the slice files themselves, zlib's gz API), geometry against the header text.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <regex>

#include "tests/readers/reader_test_util.h"

namespace voxlink::sources::testing {

namespace {

TEST(NrrdReader, HeadsqOneRawFilePerSliceEqualsTheSlicesConcatenated) {
  VOXLINK_REQUIRE_DATA("ct/vtk_headsq/quarter.nhdr");
  auto source = openOrDie(dataPath("ct/vtk_headsq/quarter.nhdr"));
  ASSERT_TRUE(source);
  const VolumeInfo& info = source->info();
  EXPECT_EQ(info.format, "nrrd");
  EXPECT_EQ(info.dims, (std::array<uint32_t, 3>{64, 64, 93}));
  EXPECT_EQ(info.type, ScalarType::kI16);
  EXPECT_EQ(info.spacing, (std::array<double, 3>{3.2, 3.2, 1.5}));
  EXPECT_TRUE(source->randomAccess());
  std::vector<uint8_t> expected;
  for (int i = 1; i <= 93; ++i) {
    const auto slice = readBytes(dataPath("ct/vtk_headsq/quarter." + std::to_string(i)));
    ASSERT_EQ(slice.size(), 64u * 64u * 2u) << i;
    expected.insert(expected.end(), slice.begin(), slice.end());
  }
  auto data = readAll(*source);
  ASSERT_TRUE(data) << data.message();
  EXPECT_TRUE(*data == expected);
  // Random access: slice 50 alone is quarter.51.
  std::vector<uint8_t> one(info.sliceBytes());
  ASSERT_TRUE(source->read(50, 1, one.data()).isOk());
  EXPECT_TRUE(one == readBytes(dataPath("ct/vtk_headsq/quarter.51")));
}

TEST(NrrdReader, Lidc2DetachedGzipEqualsZlibGunzip) {
  VOXLINK_REQUIRE_DATA("ct/vtkjs_LIDC2/LIDC2.nhdr");
  auto source = openOrDie(dataPath("ct/vtkjs_LIDC2/LIDC2.nhdr"));
  ASSERT_TRUE(source);
  const VolumeInfo& info = source->info();
  EXPECT_EQ(info.dims, (std::array<uint32_t, 3>{256, 256, 133}));
  EXPECT_EQ(info.type, ScalarType::kU8);
  EXPECT_EQ(info.spacing, (std::array<double, 3>{1.40625, 1.40625, 2.5}));
  EXPECT_FALSE(source->randomAccess());
  const auto expected = gunzipFile(dataPath("ct/vtkjs_LIDC2/b1ad142a1ebc80f957fcdc329e876d51.gz"));
  ASSERT_EQ(expected.size(), 256u * 256u * 133u);
  auto data = readAll(*source);
  ASSERT_TRUE(data) << data.message();
  EXPECT_TRUE(*data == expected);
}

// The lossy previews: dims and type from the file name, spacing from the original metadata
// (.json: spacing * original size / preview size), values from zlib on the attached bytes.
TEST(NrrdReader, OpenScivisAttachedGzipPreviews) {
  VOXLINK_REQUIRE_DATA("ct/openscivis_lossy/foot.json");
  struct Case {
    const char* file;
    std::array<double, 3> spacing;  // from <name>.json
  } cases[] = {
      {"foot_256x256x256_uint8_lossy.nrrd", {1.0, 1.0, 1.0}},
      {"engine_256x256x128_uint8_lossy.nrrd", {1.0, 1.0, 1.0}},
      {"carp_128x128x256_uint16_lossy.nrrd", {0.78125 * 2, 0.390625 * 2, 1.0 * 2}},
      {"stag_beetle_416x208x124_uint16_lossy.nrrd",
       {1.0 * 832 / 416, 1.0 * 832 / 208, 1.0 * 494 / 124}},
  };
  const std::regex name(R"(_(\d+)x(\d+)x(\d+)_(uint8|uint16)_)");
  for (const Case& c : cases) {
    SCOPED_TRACE(c.file);
    const std::string path = dataPath(std::string("ct/openscivis_lossy/") + c.file);
    std::cmatch m;
    ASSERT_TRUE(std::regex_search(c.file, m, name));
    auto source = openOrDie(path);
    ASSERT_TRUE(source);
    const VolumeInfo& info = source->info();
    EXPECT_EQ(info.dims,
              (std::array<uint32_t, 3>{uint32_t(std::stoul(m[1])), uint32_t(std::stoul(m[2])),
                                       uint32_t(std::stoul(m[3]))}));
    EXPECT_EQ(info.type, m[4] == "uint8" ? ScalarType::kU8 : ScalarType::kU16);
    for (int a = 0; a < 3; ++a)
      EXPECT_NEAR(info.spacing[a], c.spacing[a], 1e-5 * c.spacing[a]) << a;
    const auto compressed = bytesAfterBlankLine(path);
    const auto expected = inflateBytes(compressed.data(), compressed.size(),
                                       info.voxelCount() * scalarSize(info.type));
    auto data = readAll(*source);
    ASSERT_TRUE(data) << data.message();
    EXPECT_TRUE(*data == expected);
  }
}

TEST(NrrdReader, FlairObliqueDirectionsGiveLengthsAndANote) {
  VOXLINK_REQUIRE_DATA("mri/niivue_FLAIR.nrrd");
  const std::string path = dataPath("mri/niivue_FLAIR.nrrd");
  auto source = openOrDie(path);
  ASSERT_TRUE(source);
  const VolumeInfo& info = source->info();
  EXPECT_EQ(info.dims, (std::array<uint32_t, 3>{124, 160, 140}));
  EXPECT_EQ(info.type, ScalarType::kU8);
  // The header's space directions, copied from the file's text.
  const double dirs[3][3] = {{-0.99359200921208746, 0.04970492721885441, -0.10151029228632795},
                             {-0.016005020190061219, -0.95093665139041228, -0.30897139733494045},
                             {-0.11188725988575336, -0.30536684015686016, 0.94563858529983524}};
  for (int a = 0; a < 3; ++a)
    EXPECT_NEAR(
        info.spacing[a],
        std::sqrt(dirs[a][0] * dirs[a][0] + dirs[a][1] * dirs[a][1] + dirs[a][2] * dirs[a][2]),
        1e-12);
  EXPECT_NEAR(info.origin[0], 64.898239135742202, 1e-9);
  EXPECT_NEAR(info.origin[1], 110.4311447143555, 1e-9);
  EXPECT_NEAR(info.origin[2], -27.92553901672364, 1e-9);
  EXPECT_TRUE(hasNote(info, "oblique")) << notesOf(info);
  const auto compressed = bytesAfterBlankLine(path);
  const auto expected = inflateBytes(compressed.data(), compressed.size(), info.voxelCount());
  auto data = readAll(*source);
  ASSERT_TRUE(data) << data.message();
  EXPECT_TRUE(*data == expected);
}

// NRRD0001 with the old "datafile:" spelling (teem lists "datafile" as an equivalent of
// "data file") and a "./" relative name.
TEST(NrrdReader, NucleonOldSpellingReadsTheRawFile) {
  VOXLINK_REQUIRE_DATA("volume/voreen_nucleon/nucleon.nrrd");
  auto source = openOrDie(dataPath("volume/voreen_nucleon/nucleon.nrrd"));
  ASSERT_TRUE(source);
  EXPECT_EQ(source->info().dims, (std::array<uint32_t, 3>{41, 41, 41}));
  EXPECT_EQ(source->info().type, ScalarType::kU8);
  auto data = readAll(*source);
  ASSERT_TRUE(data) << data.message();
  EXPECT_TRUE(*data == readBytes(dataPath("volume/voreen_nucleon/nucleon.raw")));
  // One raw file: the zero-copy path is offered.
  EXPECT_NE(source->map(0, 41), nullptr);
}

TEST(NrrdReader, EveryTeemTypeSpellingMapsToItsType) {
  TempDir dir;
  const std::pair<const char*, ScalarType> spellings[] = {{"signed char", ScalarType::kI8},
                                                          {"int8", ScalarType::kI8},
                                                          {"int8_t", ScalarType::kI8},
                                                          {"uchar", ScalarType::kU8},
                                                          {"unsigned char", ScalarType::kU8},
                                                          {"uint8", ScalarType::kU8},
                                                          {"uint8_t", ScalarType::kU8},
                                                          {"short", ScalarType::kI16},
                                                          {"short int", ScalarType::kI16},
                                                          {"signed short", ScalarType::kI16},
                                                          {"signed short int", ScalarType::kI16},
                                                          {"int16", ScalarType::kI16},
                                                          {"int16_t", ScalarType::kI16},
                                                          {"ushort", ScalarType::kU16},
                                                          {"unsigned short", ScalarType::kU16},
                                                          {"unsigned short int", ScalarType::kU16},
                                                          {"uint16", ScalarType::kU16},
                                                          {"uint16_t", ScalarType::kU16},
                                                          {"int", ScalarType::kI32},
                                                          {"signed int", ScalarType::kI32},
                                                          {"int32", ScalarType::kI32},
                                                          {"int32_t", ScalarType::kI32},
                                                          {"uint", ScalarType::kU32},
                                                          {"unsigned int", ScalarType::kU32},
                                                          {"uint32", ScalarType::kU32},
                                                          {"uint32_t", ScalarType::kU32},
                                                          {"float", ScalarType::kF32},
                                                          {"double", ScalarType::kF64},
                                                          {"UCHAR", ScalarType::kU8}};
  for (const auto& [name, type] : spellings) {
    SCOPED_TRACE(name);
    const std::string path = dir.file("t.nrrd");
    const auto data = patternBytes(2 * 3 * 4 * scalarSize(type));
    writeWithHeader(path,
                    cat("NRRD0004\ntype: ", name,
                        "\ndimension: 3\nsizes: 2 3 4\nendian: little\nencoding: raw\n\n"),
                    data);
    auto source = openOrDie(path);
    ASSERT_TRUE(source);
    EXPECT_EQ(source->info().type, type);
    auto read = readAll(*source);
    ASSERT_TRUE(read) << read.message();
    EXPECT_TRUE(*read == data);
  }
}

TEST(NrrdReader, BigEndianShortsAreSwapped) {
  TempDir dir;
  const auto big = patternBytes(4 * 4 * 3 * 2, 7);
  writeWithHeader(
      dir.file("b.nrrd"),
      "NRRD0004\ntype: short\ndimension: 3\nsizes: 4 4 3\nendian: big\nencoding: raw\n\n", big);
  auto source = openOrDie(dir.file("b.nrrd"));
  ASSERT_TRUE(source);
  auto data = readAll(*source);
  ASSERT_TRUE(data) << data.message();
  EXPECT_TRUE(*data == swapped(big, 2));
  EXPECT_EQ(source->map(0, 1), nullptr);  // swapped data is never served in place
}

TEST(NrrdReader, SkipsListsPatternsAndFourDimensions) {
  TempDir dir;
  const auto slices = patternBytes(5 * 4 * 6, 3);
  auto slice = [&](int z) {
    return std::vector<uint8_t>(slices.begin() + z * 20, slices.begin() + (z + 1) * 20);
  };
  // %03d numbering from 0 with step 2, two slices per file, line skip and byte skip.
  for (int f = 0; f < 3; ++f) {
    std::vector<uint8_t> bytes = {'a', '\n', 'b', '\n', 'X', 'Y', 'Z'};
    for (int z = 2 * f; z < 2 * f + 2; ++z) {
      const auto s = slice(z);
      bytes.insert(bytes.end(), s.begin(), s.end());
    }
    writeBytes(dir.file(cat("part", f * 2 < 10 ? "00" : "0", f * 2, ".bin")), bytes);
  }
  writeText(dir.file("pattern.nhdr"),
            "NRRD0005\ntype: uint8\ndimension: 3\nsizes: 5 4 6\nencoding: raw\n"
            "line skip: 2\nbyte skip: 3\ndata file: part%03d.bin 0 4 2\n");
  // LIST form, one file per slice, gzip, 4-D with a leading axis of size 1.
  std::string list =
      "NRRD0004\ntype: uchar\ndimension: 4\nsizes: 1 5 4 6\nspacings: nan 0.5 0.25 2\nencoding: "
      "gzip\ndata file: LIST\n";
  for (int z = 0; z < 6; ++z) {
    writeBytes(dir.file(cat("s", z, ".gz")), gzipBytes(slice(z)));
    list += cat("s", z, ".gz\n");
  }
  writeText(dir.file("list.nhdr"), list);
  // byte skip -1: the data is the end of the file.
  std::vector<uint8_t> withJunk = patternBytes(33, 9);
  withJunk.insert(withJunk.end(), slices.begin(), slices.end());
  writeBytes(dir.file("tail.raw"), withJunk);
  writeText(dir.file("tail.nhdr"),
            "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 5 4 6\nencoding: raw\nbyte skip: -1\ndata "
            "file: tail.raw\n");

  for (const char* name : {"pattern.nhdr", "list.nhdr", "tail.nhdr"}) {
    SCOPED_TRACE(name);
    auto source = openOrDie(dir.file(name));
    ASSERT_TRUE(source);
    EXPECT_EQ(source->info().dims, (std::array<uint32_t, 3>{5, 4, 6}));
    auto data = readAll(*source);
    ASSERT_TRUE(data) << data.message();
    EXPECT_TRUE(*data == slices);
  }
  auto four = openOrDie(dir.file("list.nhdr"));
  ASSERT_TRUE(four);
  EXPECT_EQ(four->info().spacing, (std::array<double, 3>{0.5, 0.25, 2}));
  EXPECT_TRUE(hasNote(four->info(), "4-D")) << notesOf(four->info());
}

TEST(NrrdReader, CommentsKeyValuePairsAndCrlfLinesAreAccepted) {
  TempDir dir;
  const auto data = patternBytes(3 * 3 * 3 * 4, 5);
  writeWithHeader(dir.file("c.nrrd"),
                  "NRRD0004\r\n# a comment\r\ntype: float\r\nmy key:=some value\r\ndimension: 3\r\n"
                  "space: right-anterior-superior\r\nsizes: 3 3 3\r\nspace directions: (0.5,0,0) "
                  "(0,0.5,0) (0,0,2)\r\n"
                  "space origin: (1, 2, 3)\r\nkinds: domain domain domain\r\nendian: "
                  "little\r\nencoding: raw\r\n\r\n",
                  data);
  auto source = openOrDie(dir.file("c.nrrd"));
  ASSERT_TRUE(source);
  EXPECT_EQ(source->info().spacing, (std::array<double, 3>{0.5, 0.5, 2}));
  EXPECT_EQ(source->info().origin, (std::array<double, 3>{1, 2, 3}));
  EXPECT_TRUE(source->info().notes.empty()) << notesOf(source->info());
  auto read = readAll(*source);
  ASSERT_TRUE(read) << read.message();
  EXPECT_TRUE(*read == data);
}

}  // namespace
}  // namespace voxlink::sources::testing
