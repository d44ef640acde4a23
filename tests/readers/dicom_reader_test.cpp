// SPDX-License-Identifier: BSD-3-Clause
// DICOM: the Slicer CT head series is the VTK headsq volume with z reversed (README), voxel for
// voxel; damaged copies (written with GDCM into a temp folder) give named errors.
#include <gdcmAttribute.h>
#include <gdcmReader.h>
#include <gdcmWriter.h>
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <functional>

#include "tests/readers/reader_test_util.h"

namespace voxlink::sources::testing {

namespace {

namespace fs = std::filesystem;
constexpr const char* kSeries = "ct/slicer_CTHeadAxialDicom";

std::vector<uint8_t> headsqBytes() {
  std::vector<uint8_t> all;
  for (int i = 1; i <= 93; ++i) {
    const auto slice = readBytes(dataPath("ct/vtk_headsq/quarter." + std::to_string(i)));
    all.insert(all.end(), slice.begin(), slice.end());
  }
  return all;
}

// Copies the series into `dir`, letting `edit` change each file's data set (by file name).
void copySeries(const TempDir& dir,
                const std::function<void(const std::string&, gdcm::DataSet&)>& edit = {}) {
  for (const auto& entry : fs::directory_iterator(dataPath(kSeries))) {
    const std::string name = entry.path().filename().string();
    if (!edit) {
      fs::copy_file(entry.path(), dir.file(name));
      continue;
    }
    gdcm::Reader reader;
    reader.SetFileName(entry.path().c_str());
    ASSERT_TRUE(reader.Read()) << name;
    edit(name, reader.GetFile().GetDataSet());
    gdcm::Writer writer;
    writer.SetFileName(dir.file(name).c_str());
    writer.SetFile(reader.GetFile());
    ASSERT_TRUE(writer.Write()) << name;
  }
}

TEST(DicomReader, CtHeadSeriesIsHeadsqWithZReversed) {
  VOXLINK_REQUIRE_DATA(kSeries);
  VOXLINK_REQUIRE_DATA("ct/vtk_headsq/quarter.nhdr");
  auto source = openOrDie(dataPath(kSeries));
  ASSERT_TRUE(source);
  const VolumeInfo& info = source->info();
  EXPECT_EQ(info.format, "dicom");
  EXPECT_EQ(info.dims, (std::array<uint32_t, 3>{64, 64, 93}));
  // PixelRepresentation 1 (signed) in these files; values 0..3926 as in headsq.
  EXPECT_EQ(info.type, ScalarType::kI16);
  EXPECT_NEAR(info.spacing[0], 3.2, 1e-9);
  EXPECT_NEAR(info.spacing[1], 3.2, 1e-9);
  EXPECT_NEAR(info.spacing[2], 1.5, 1e-9);
  EXPECT_TRUE(hasNote(info, "sorted by position along the slice normal")) << notesOf(info);
  auto data = readAll(*source);
  ASSERT_TRUE(data) << data.message();
  EXPECT_TRUE(*data == flipZ(headsqBytes(), info.sliceBytes()));
}

TEST(DicomReader, RescaleInterceptIsAppliedAsExactIntegers) {
  VOXLINK_REQUIRE_DATA(kSeries);
  TempDir dir;
  copySeries(dir, [](const std::string&, gdcm::DataSet& ds) {
    gdcm::Attribute<0x0028, 0x1052> intercept;
    intercept.SetValue(-1024.0);
    ds.Replace(intercept.GetAsDataElement());
  });
  auto source = openOrDie(dir.path().string());
  ASSERT_TRUE(source);
  // BitsStored 16, signed: [-32768, 32767] - 1024 needs i32.
  EXPECT_EQ(source->info().type, ScalarType::kI32);
  EXPECT_TRUE(hasNote(source->info(), "RescaleSlope/RescaleIntercept applied"))
      << notesOf(source->info());
  auto data = readAll(*source);
  ASSERT_TRUE(data) << data.message();
  const auto expected = flipZ(headsqBytes(), 64 * 64 * 2);
  ASSERT_EQ(data->size(), expected.size() * 2);
  for (size_t i = 0; i < expected.size() / 2; ++i) {
    int16_t want;
    int32_t got;
    std::memcpy(&want, expected.data() + 2 * i, 2);
    std::memcpy(&got, data->data() + 4 * i, 4);
    ASSERT_EQ(got, want - 1024) << i;
  }
}

TEST(DicomReader, InconsistentSliceSizeNamesTheFileAndTag) {
  VOXLINK_REQUIRE_DATA(kSeries);
  TempDir dir;
  copySeries(dir, [](const std::string& name, gdcm::DataSet& ds) {
    if (name != "CTHead40.dcm") return;
    gdcm::Attribute<0x0028, 0x0010> rows;
    rows.SetValue(32);
    ds.Replace(rows.GetAsDataElement());
    gdcm::Attribute<0x0028, 0x0011> columns;
    columns.SetValue(32);
    ds.Replace(columns.GetAsDataElement());
    std::vector<char> pixels(32 * 32 * 2, 0);
    gdcm::DataElement pixel(gdcm::Tag(0x7fe0, 0x0010));
    pixel.SetVR(gdcm::VR::OW);
    pixel.SetByteValue(pixels.data(), static_cast<uint32_t>(pixels.size()));
    ds.Replace(pixel);
  });
  expectError(openVolume(dir.path().string()), ErrorCode::kSizeMismatch,
              {"CTHead40.dcm", "Rows x Columns", "32x32", "64x64"});
}

// Cut files: one cut inside its pixel data (GDCM reads it without complaint, the reader must
// not), and one cut inside its header, where Debian's GDCM asserts and would abort the process.
TEST(DicomReader, CutFilesAreNamedNotReadOrCrashedOn) {
  VOXLINK_REQUIRE_DATA(kSeries);
  TempDir dir;
  copySeries(dir);
  const std::string victim = dir.file("CTHead50.dcm");
  const auto whole = readBytes(victim);
  writeBytes(victim, std::vector<uint8_t>(whole.begin(), whole.end() - 1));
  expectError(openVolume(dir.path().string()), ErrorCode::kTruncated,
              {"CTHead50.dcm", "PixelData (7FE0,0010)", "8191 bytes", "need 8192"});
  writeBytes(victim, std::vector<uint8_t>(whole.begin(), whole.begin() + 300));
  expectError(openVolume(dir.path().string()), ErrorCode::kCorrupt,
              {"CTHead50.dcm", "GDCM crashed"});
  writeBytes(victim, whole);
  EXPECT_TRUE(openOrDie(dir.path().string()));
}

TEST(DicomReader, MissingSliceMakesGapsNonUniform) {
  VOXLINK_REQUIRE_DATA(kSeries);
  TempDir dir;
  copySeries(dir);
  fs::remove(dir.file("CTHead50.dcm"));
  expectError(
      openVolume(dir.path().string()), ErrorCode::kUnsupported,
      {dir.path().string(), "ImagePositionPatient", "not uniform", "CTHead49.dcm", "CTHead51.dcm"});
}

TEST(DicomReader, TwoFilesAtOnePositionAreRefused) {
  VOXLINK_REQUIRE_DATA(kSeries);
  TempDir dir;
  copySeries(dir);
  fs::copy_file(dir.file("CTHead7.dcm"), dir.file("CTHead7copy.dcm"));
  expectError(openVolume(dir.path().string()), ErrorCode::kCorrupt,
              {"ImagePositionPatient", "CTHead7", "same slice position"});
}

TEST(DicomReader, TwoSeriesInOneFolderAreRefused) {
  VOXLINK_REQUIRE_DATA(kSeries);
  TempDir dir;
  copySeries(dir, [](const std::string& name, gdcm::DataSet& ds) {
    if (name != "CTHead3.dcm") return;
    gdcm::Attribute<0x0020, 0x000e> uid;
    uid.SetValue("1.2.3.4.5");
    ds.Replace(uid.GetAsDataElement());
  });
  expectError(openVolume(dir.path().string()), ErrorCode::kUnsupported,
              {"SeriesInstanceUID", "holds 2 series"});
}

TEST(DicomReader, OtherFilesInTheFolderAreSkippedWithANote) {
  VOXLINK_REQUIRE_DATA(kSeries);
  TempDir dir;
  copySeries(dir);
  writeText(dir.file("README.txt"), "not an image\n");
  auto source = openOrDie(dir.path().string());
  ASSERT_TRUE(source);
  EXPECT_EQ(source->info().dims[2], 93u);
  EXPECT_TRUE(hasNote(source->info(), "1 non-DICOM files")) << notesOf(source->info());
}

}  // namespace
}  // namespace voxlink::sources::testing
