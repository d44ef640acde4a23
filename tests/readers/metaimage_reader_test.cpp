// SPDX-License-Identifier: BSD-3-Clause
// MetaImage on the real files, values checked against zlib's own decoding of the same bytes
// or the raw file itself.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>

#include "tests/readers/reader_test_util.h"

namespace voxlink::sources::testing {

namespace {

// The header names "HeadMRVolume.raw"; the shared data holds it as vtk_HeadMRVolume.raw.
TEST(MetaImageReader, HeadMrMissingDataFileIsNamedWithAHint) {
  VOXLINK_REQUIRE_DATA("mri/vtk_HeadMRVolume.mhd");
  auto r = openVolume(dataPath("mri/vtk_HeadMRVolume.mhd"));
  expectError(r, ErrorCode::kIo,
              {"vtk_HeadMRVolume.mhd", "ElementDataFile", "HeadMRVolume.raw does not exist",
               "vtk_HeadMRVolume.raw is there"});
}

TEST(MetaImageReader, HeadMrWithItsDataFileBesideItEqualsTheRawBytes) {
  VOXLINK_REQUIRE_DATA("mri/vtk_HeadMRVolume.mhd");
  TempDir dir;
  std::filesystem::copy_file(dataPath("mri/vtk_HeadMRVolume.mhd"), dir.file("HeadMRVolume.mhd"));
  std::filesystem::copy_file(dataPath("mri/vtk_HeadMRVolume.raw"), dir.file("HeadMRVolume.raw"));
  auto source = openOrDie(dir.file("HeadMRVolume.mhd"));
  ASSERT_TRUE(source);
  const VolumeInfo& info = source->info();
  EXPECT_EQ(info.format, "metaimage");
  EXPECT_EQ(info.dims, (std::array<uint32_t, 3>{48, 62, 42}));
  EXPECT_EQ(info.type, ScalarType::kU8);
  EXPECT_EQ(info.spacing, (std::array<double, 3>{4, 4, 4}));
  auto data = readAll(*source);
  ASSERT_TRUE(data) << data.message();
  EXPECT_TRUE(*data == readBytes(dataPath("mri/vtk_HeadMRVolume.raw")));
}

TEST(MetaImageReader, FrogtissueZrawEqualsZlibUncompress) {
  VOXLINK_REQUIRE_DATA("volume/vtk_frogtissue/frogtissue.mhd");
  auto source = openOrDie(dataPath("volume/vtk_frogtissue/frogtissue.mhd"));
  ASSERT_TRUE(source);
  const VolumeInfo& info = source->info();
  EXPECT_EQ(info.dims, (std::array<uint32_t, 3>{500, 470, 136}));
  EXPECT_EQ(info.type, ScalarType::kU8);
  EXPECT_EQ(info.spacing, (std::array<double, 3>{1, 1, 1.5}));
  // The header's CompressedDataSize (260020) is not the file's size (262087).
  EXPECT_TRUE(hasNote(info, "CompressedDataSize 260020")) << notesOf(info);
  const auto zraw = readBytes(dataPath("volume/vtk_frogtissue/frogtissue.zraw"));
  const auto expected = inflateBytes(zraw.data(), zraw.size(), info.voxelCount());
  auto data = readAll(*source);
  ASSERT_TRUE(data) << data.message();
  EXPECT_TRUE(*data == expected);
  // README: labels 0..29, 3.6 % non-zero.
  EXPECT_EQ(*std::max_element(data->begin(), data->end()), 29);
  const double nonZero = static_cast<double>(std::count_if(data->begin(), data->end(),
                                                           [](uint8_t v) { return v != 0; })) /
                         static_cast<double>(data->size());
  EXPECT_NEAR(nonZero, 0.036, 0.0005);
}

TEST(MetaImageReader, NiivueMhaLocalZlibData) {
  VOXLINK_REQUIRE_DATA("mri/niivue_mha.mha");
  const std::string path = dataPath("mri/niivue_mha.mha");
  auto source = openOrDie(path);
  ASSERT_TRUE(source);
  const VolumeInfo& info = source->info();
  EXPECT_EQ(info.dims, (std::array<uint32_t, 3>{64, 64, 37}));
  EXPECT_EQ(info.type, ScalarType::kI16);
  EXPECT_DOUBLE_EQ(info.spacing[0], 3.4375000000000009);
  EXPECT_DOUBLE_EQ(info.spacing[2], 3.7999999999999994);
  EXPECT_DOUBLE_EQ(info.origin[0], -108.28100000000002);
  EXPECT_DOUBLE_EQ(info.origin[1], 82.379500000000007);
  EXPECT_TRUE(hasNote(info, "+x -y +z")) << notesOf(info);  // TransformMatrix 1 0 0 0 -1 0 0 0 1
  const auto all = readBytes(path);
  const std::string marker = "ElementDataFile = LOCAL\n";
  const auto at = std::search(all.begin(), all.end(), marker.begin(), marker.end());
  ASSERT_NE(at, all.end());
  const size_t offset = static_cast<size_t>(at - all.begin()) + marker.size();
  const auto expected =
      inflateBytes(all.data() + offset, all.size() - offset, info.voxelCount() * 2);
  auto data = readAll(*source);
  ASSERT_TRUE(data) << data.message();
  EXPECT_TRUE(*data == expected);
}

TEST(MetaImageReader, ElementTypesByteOrderListsAndHeaderSize) {
  TempDir dir;
  const std::pair<const char*, ScalarType> types[] = {
      {"MET_CHAR", ScalarType::kI8},   {"MET_UCHAR", ScalarType::kU8},
      {"MET_SHORT", ScalarType::kI16}, {"MET_USHORT", ScalarType::kU16},
      {"MET_INT", ScalarType::kI32},   {"MET_UINT", ScalarType::kU32},
      {"MET_LONG", ScalarType::kI32},  {"MET_ULONG", ScalarType::kU32},
      {"MET_FLOAT", ScalarType::kF32}, {"MET_DOUBLE", ScalarType::kF64}};
  for (const auto& [name, type] : types) {
    SCOPED_TRACE(name);
    const auto data = patternBytes(3 * 2 * 2 * scalarSize(type), 11);
    writeWithHeader(dir.file("t.mha"),
                    cat("NDims = 3\nDimSize = 3 2 2\nElementType = ", name,
                        "\nBinaryDataByteOrderMSB = True\nElementDataFile = LOCAL\n"),
                    data);
    auto source = openOrDie(dir.file("t.mha"));
    ASSERT_TRUE(source);
    EXPECT_EQ(source->info().type, type);
    auto read = readAll(*source);
    ASSERT_TRUE(read) << read.message();
    EXPECT_TRUE(*read == swapped(data, scalarSize(type)));
  }

  const auto slices = patternBytes(4 * 3 * 4, 13);
  for (int z = 0; z < 4; ++z) {
    std::vector<uint8_t> file = patternBytes(10, 99);  // a 10-byte header in each data file
    file.insert(file.end(), slices.begin() + z * 12, slices.begin() + (z + 1) * 12);
    writeBytes(dir.file(cat("img", z + 1, ".raw")), file);
  }
  writeText(dir.file("list.mhd"),
            "ObjectType = Image\nNDims = 3\nDimSize = 4 3 4\nElementSize = 2 2 3\n"
            "ElementType = MET_UCHAR\nHeaderSize = 10\nElementDataFile = "
            "LIST\nimg1.raw\nimg2.raw\nimg3.raw\nimg4.raw\n");
  writeText(dir.file("pattern.mhd"),
            "NDims = 3\nDimSize = 4 3 4\nElementType = MET_UCHAR\nHeaderSize = -1\n"
            "ElementDataFile = img%d.raw 1 4 1\n");
  for (const char* name : {"list.mhd", "pattern.mhd"}) {
    SCOPED_TRACE(name);
    auto source = openOrDie(dir.file(name));
    ASSERT_TRUE(source);
    auto read = readAll(*source);
    ASSERT_TRUE(read) << read.message();
    EXPECT_TRUE(*read == slices);
  }
  auto list = openOrDie(dir.file("list.mhd"));
  ASSERT_TRUE(list);
  EXPECT_EQ(list->info().spacing, (std::array<double, 3>{2, 2, 3}));
  EXPECT_TRUE(hasNote(list->info(), "ElementSize")) << notesOf(list->info());
}

}  // namespace
}  // namespace voxlink::sources::testing
