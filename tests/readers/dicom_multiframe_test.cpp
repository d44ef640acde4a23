// SPDX-License-Identifier: BSD-3-Clause
// DICOM multi-frame files and folders as scanners and planning systems write them: the shared
// RT Dose grid against its own pixel bytes; Enhanced CT rewrites of the CT head series (built
// here with GDCM; uncompressed, RLE, JPEG-LS, JPEG 2000) against the series itself; several series
// in nested folders; images without positions; damaged functional groups.
#include <gdcmAttribute.h>
#include <gdcmImageChangeTransferSyntax.h>
#include <gdcmImageReader.h>
#include <gdcmImageWriter.h>
#include <gdcmReader.h>
#include <gdcmSequenceOfItems.h>
#include <gdcmWriter.h>
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <functional>

#include "sources/readers/dicom_reader.h"
#include "tests/readers/reader_test_util.h"

namespace voxlink::sources::testing {

namespace {

namespace fs = std::filesystem;
constexpr const char* kSeries = "ct/slicer_CTHeadAxialDicom";
constexpr const char* kDose = "dicom_multiframe/pydicom_rtdose.dcm";

gdcm::DataElement text(uint16_t g, uint16_t e, gdcm::VR vr, std::string value) {
  if (value.size() % 2) value += ' ';
  gdcm::DataElement de(gdcm::Tag(g, e));
  de.SetVR(vr);
  de.SetByteValue(value.data(), static_cast<uint32_t>(value.size()));
  return de;
}

gdcm::DataSet itemOf(std::initializer_list<gdcm::DataElement> elements) {
  gdcm::DataSet ds;
  for (const gdcm::DataElement& e : elements) ds.Insert(e);
  return ds;
}

gdcm::DataElement sequence(uint16_t g, uint16_t e, const std::vector<gdcm::DataSet>& items) {
  gdcm::SmartPointer<gdcm::SequenceOfItems> sq = new gdcm::SequenceOfItems;
  sq->SetLengthToUndefined();
  for (const gdcm::DataSet& ds : items) {
    gdcm::Item item;
    item.SetVLToUndefined();
    item.SetNestedDataSet(ds);
    sq->AddItem(item);
  }
  gdcm::DataElement de(gdcm::Tag(g, e));
  de.SetVR(gdcm::VR::SQ);
  de.SetValue(*sq);
  de.SetVLToUndefined();
  return de;
}

const gdcm::DataElement& element(const gdcm::DataSet& ds, uint16_t g, uint16_t e) {
  return ds.GetDataElement(gdcm::Tag(g, e));
}

using FrameHook = std::function<void(uint32_t frame, gdcm::DataSet& perFrameGroup)>;
using TopHook = std::function<void(gdcm::DataSet& ds)>;

// An Enhanced CT file holding CTHead<order[k]>.dcm as frame k: per-frame PlanePositionSequence
// (each slice's ImagePositionPatient), shared PlaneOrientationSequence and PixelMeasuresSequence;
// the top-level position, orientation and spacing are removed so only the groups can give them.
void writeEnhancedHeadsq(const std::string& out, const std::vector<int>& order,
                         const FrameHook& perFrame = {}, const TopHook& top = {}) {
  gdcm::Reader base;
  const std::string first = dataPath(std::string(kSeries) + "/CTHead1.dcm");
  base.SetFileName(first.c_str());
  ASSERT_TRUE(base.Read());
  gdcm::DataSet& ds = base.GetFile().GetDataSet();
  std::vector<char> pixels;
  std::vector<gdcm::DataSet> frames;
  for (uint32_t k = 0; k < order.size(); ++k) {
    const std::string file = dataPath(cat(kSeries, "/CTHead", order[k], ".dcm"));
    gdcm::ImageReader slice;
    slice.SetFileName(file.c_str());
    ASSERT_TRUE(slice.Read()) << file;
    std::vector<char> buffer(slice.GetImage().GetBufferLength());
    ASSERT_TRUE(slice.GetImage().GetBuffer(buffer.data()));
    pixels.insert(pixels.end(), buffer.begin(), buffer.end());
    const gdcm::DataSet& sds = slice.GetFile().GetDataSet();
    gdcm::DataSet group =
        itemOf({sequence(0x0020, 0x9113, {itemOf({element(sds, 0x0020, 0x0032)})})});
    if (perFrame) perFrame(k, group);
    frames.push_back(group);
  }
  const gdcm::DataSet shared =
      itemOf({sequence(0x0020, 0x9116, {itemOf({element(ds, 0x0020, 0x0037)})}),
              sequence(0x0028, 0x9110,
                       {itemOf({element(ds, 0x0028, 0x0030), element(ds, 0x0018, 0x0050)})})});
  for (const gdcm::Tag& t :
       {gdcm::Tag(0x0020, 0x0032), gdcm::Tag(0x0020, 0x0037), gdcm::Tag(0x0028, 0x0030),
        gdcm::Tag(0x0028, 0x1052), gdcm::Tag(0x0028, 0x1053)})
    ds.Remove(t);
  ds.Replace(text(0x0008, 0x0016, gdcm::VR::UI, "1.2.840.10008.5.1.4.1.1.2.1"));
  ds.Replace(text(0x0028, 0x0008, gdcm::VR::IS, std::to_string(order.size())));
  ds.Replace(sequence(0x5200, 0x9229, {shared}));
  ds.Replace(sequence(0x5200, 0x9230, frames));
  gdcm::DataElement pixel(gdcm::Tag(0x7fe0, 0x0010));
  pixel.SetVR(gdcm::VR::OW);
  pixel.SetByteValue(pixels.data(), static_cast<uint32_t>(pixels.size()));
  ds.Replace(pixel);
  if (top) top(ds);
  gdcm::Writer writer;
  writer.SetFileName(out.c_str());
  writer.SetFile(base.GetFile());
  ASSERT_TRUE(writer.Write());
}

// The same file in another transfer syntax, compressed by GDCM.
void recompress(const std::string& in, const std::string& out, const gdcm::TransferSyntax& ts) {
  gdcm::ImageReader reader;
  reader.SetFileName(in.c_str());
  ASSERT_TRUE(reader.Read());
  gdcm::ImageChangeTransferSyntax change;
  change.SetTransferSyntax(ts);
  change.SetInput(reader.GetImage());
  ASSERT_TRUE(change.Change());
  gdcm::ImageWriter writer;
  writer.SetFileName(out.c_str());
  writer.SetFile(reader.GetFile());
  writer.SetImage(change.GetOutput());
  ASSERT_TRUE(writer.Write());
}

std::vector<int> reversedSlices() {
  std::vector<int> order;
  for (int i = 93; i >= 1; --i) order.push_back(i);
  return order;
}

TEST(DicomMultiFrame, RtDoseIsItsPixelBytesTimesDoseGridScaling) {
  VOXLINK_REQUIRE_DATA(kDose);
  auto source = openOrDie(dataPath(kDose));
  ASSERT_TRUE(source);
  const VolumeInfo& info = source->info();
  EXPECT_EQ(info.format, "dicom");
  EXPECT_EQ(info.dims, (std::array<uint32_t, 3>{10, 10, 15}));
  EXPECT_EQ(info.type, ScalarType::kF64);  // u32 * 1e-6: f32 could not hold every value
  EXPECT_NEAR(info.spacing[0], 10, 1e-9);
  EXPECT_NEAR(info.spacing[1], 10, 1e-9);
  EXPECT_NEAR(info.spacing[2], 5, 1e-9);  // GridFrameOffsetVector 0, 5, ..., 70
  EXPECT_NEAR(info.origin[0], 189.43125, 1e-9);
  EXPECT_NEAR(info.origin[2], -761.87, 1e-9);
  ASSERT_TRUE(info.rescale);
  EXPECT_EQ(info.rescale->field, "DoseGridScaling");
  EXPECT_EQ(info.rescale->minSlope, 1e-6);
  EXPECT_TRUE(hasNote(info, "DoseGridScaling applied")) << notesOf(info);
  // Implicit VR little endian, PixelData last: the file's final 10x10x15x4 bytes, frames in
  // increasing offset order.
  const auto file = readBytes(dataPath(kDose));
  ASSERT_GE(file.size(), 6000u);
  auto data = readAll(*source);
  ASSERT_TRUE(data) << data.message();
  ASSERT_EQ(data->size(), 1500u * 8);
  for (size_t i = 0; i < 1500; ++i) {
    uint32_t stored;
    double got;
    std::memcpy(&stored, file.data() + file.size() - 6000 + 4 * i, 4);
    std::memcpy(&got, data->data() + 8 * i, 8);
    ASSERT_EQ(got, stored * 1e-6) << i;
  }
  EXPECT_EQ(readInSlabs(*source, 4), *data);
}

TEST(DicomMultiFrame, EnhancedCtRewriteOfTheSeriesGivesTheSameVoxels) {
  VOXLINK_REQUIRE_DATA(kSeries);
  auto series = openOrDie(dataPath(kSeries));
  ASSERT_TRUE(series);
  auto expected = readAll(*series);
  ASSERT_TRUE(expected) << expected.message();
  TempDir dir;
  const std::string plain = dir.file("enhanced.dcm");
  writeEnhancedHeadsq(plain, reversedSlices());
  recompress(plain, dir.file("rle.dcm"), gdcm::TransferSyntax::RLELossless);
  recompress(plain, dir.file("jpegls.dcm"), gdcm::TransferSyntax::JPEGLSLossless);
  recompress(plain, dir.file("j2k.dcm"), gdcm::TransferSyntax::JPEG2000Lossless);
  for (const char* name : {"enhanced.dcm", "rle.dcm", "jpegls.dcm", "j2k.dcm"}) {
    SCOPED_TRACE(name);
    auto source = openOrDie(dir.file(name));
    ASSERT_TRUE(source);
    const VolumeInfo& info = source->info();
    EXPECT_EQ(info.dims, series->info().dims);
    EXPECT_EQ(info.type, series->info().type);
    for (int a = 0; a < 3; ++a) {
      EXPECT_NEAR(info.spacing[a], series->info().spacing[a], 1e-9);
      EXPECT_NEAR(info.origin[a], series->info().origin[a], 1e-9);
    }
    EXPECT_TRUE(hasNote(info, "reverse of frame order")) << notesOf(info);
    EXPECT_TRUE(hasNote(info, "PlanePositionSequence")) << notesOf(info);
    auto data = readAll(*source);
    ASSERT_TRUE(data) << data.message();
    EXPECT_TRUE(*data == *expected);
    EXPECT_EQ(readInSlabs(*source, 7), *expected);
  }
}

TEST(DicomMultiFrame, PerFrameRescaleIsAppliedFrameByFrameAndRecorded) {
  VOXLINK_REQUIRE_DATA(kSeries);
  auto series = openOrDie(dataPath(kSeries));
  ASSERT_TRUE(series);
  auto expected = readAll(*series);
  ASSERT_TRUE(expected);
  TempDir dir;
  // Frame k holds CTHead<93 - k>, which sorts to z = 92 - k; it gets intercept -k.
  writeEnhancedHeadsq(dir.file("r.dcm"), reversedSlices(), [](uint32_t k, gdcm::DataSet& group) {
    group.Insert(
        sequence(0x0028, 0x9145,
                 {itemOf({text(0x0028, 0x1052, gdcm::VR::DS, std::to_string(-static_cast<int>(k))),
                          text(0x0028, 0x1053, gdcm::VR::DS, "1")})}));
  });
  auto source = openOrDie(dir.file("r.dcm"));
  ASSERT_TRUE(source);
  EXPECT_EQ(source->info().type, ScalarType::kI32);
  ASSERT_TRUE(source->info().rescale);
  EXPECT_EQ(source->info().rescale->minIntercept, -92);
  EXPECT_EQ(source->info().rescale->maxIntercept, 0);
  EXPECT_TRUE(hasNote(source->info(), "applied per slice")) << notesOf(source->info());
  auto data = readAll(*source);
  ASSERT_TRUE(data) << data.message();
  ASSERT_EQ(data->size(), expected->size() * 2);
  for (size_t i = 0; i < expected->size() / 2; ++i) {
    int16_t want;
    int32_t got;
    std::memcpy(&want, expected->data() + 2 * i, 2);
    std::memcpy(&got, data->data() + 4 * i, 4);
    const int z = static_cast<int>(i / (64 * 64));
    ASSERT_EQ(got, want - (92 - z)) << i;
  }
}

TEST(DicomMultiFrame, DamagedFunctionalGroupsGiveOneLineErrors) {
  VOXLINK_REQUIRE_DATA(kSeries);
  TempDir dir;
  const std::string f = dir.file("bad.dcm");
  // More frames claimed than the pixel data holds.
  writeEnhancedHeadsq(f, reversedSlices(), {}, [](gdcm::DataSet& ds) {
    ds.Replace(text(0x0028, 0x0008, gdcm::VR::IS, "94"));
  });
  expectError(openVolume(f), ErrorCode::kTruncated,
              {"bad.dcm", "PixelData (7FE0,0010)", "NumberOfFrames", "need 770048"});
  // Fewer frames claimed than per-frame groups.
  writeEnhancedHeadsq(f, reversedSlices(), {}, [](gdcm::DataSet& ds) {
    ds.Replace(text(0x0028, 0x0008, gdcm::VR::IS, "92"));
  });
  expectError(openVolume(f), ErrorCode::kCorrupt,
              {"bad.dcm", "PerFrameFunctionalGroupsSequence (5200,9230)", "93 items", "says 92"});
  // The functional groups removed from an Enhanced CT image.
  writeEnhancedHeadsq(f, reversedSlices(), {}, [](gdcm::DataSet& ds) {
    ds.Remove(gdcm::Tag(0x5200, 0x9229));
    ds.Remove(gdcm::Tag(0x5200, 0x9230));
  });
  expectError(openVolume(f), ErrorCode::kCorrupt,
              {"bad.dcm", "PerFrameFunctionalGroupsSequence (5200,9230) missing", "Enhanced CT"});
  // One frame tilted against the others.
  writeEnhancedHeadsq(f, reversedSlices(), [](uint32_t k, gdcm::DataSet& group) {
    if (k == 40)
      group.Insert(sequence(
          0x0020, 0x9116, {itemOf({text(0x0020, 0x0037, gdcm::VR::DS, "1\\0\\0\\0\\0.8\\0.6")})}));
  });
  expectError(
      openVolume(f), ErrorCode::kUnsupported,
      {"bad.dcm", "PlaneOrientationSequence (0020,9116)", "frame 41", "mixed orientations"});
}

// Copies the CT head series into `dir`, letting `edit` change each file's data set.
void copySeries(const fs::path& dir,
                const std::function<void(const std::string&, gdcm::DataSet&)>& edit) {
  fs::create_directories(dir);
  for (const auto& entry : fs::directory_iterator(dataPath(kSeries))) {
    const std::string name = entry.path().filename().string();
    gdcm::Reader reader;
    reader.SetFileName(entry.path().c_str());
    ASSERT_TRUE(reader.Read()) << name;
    if (edit) edit(name, reader.GetFile().GetDataSet());
    gdcm::Writer writer;
    writer.SetFileName((dir / name).c_str());
    writer.SetFile(reader.GetFile());
    ASSERT_TRUE(writer.Write()) << name;
  }
}

TEST(DicomFolders, SeveralSeriesInNestedFoldersAreListedAndPicked) {
  VOXLINK_REQUIRE_DATA(kSeries);
  VOXLINK_REQUIRE_DATA(kDose);
  TempDir dir;
  copySeries(dir.path() / "PAT1" / "CT", {});
  copySeries(dir.path() / "PAT1" / "deeper" / "CT2", [](const std::string&, gdcm::DataSet& ds) {
    ds.Replace(text(0x0020, 0x000e, gdcm::VR::UI, "1.2.3.4.5"));
  });
  fs::copy_file(dataPath(kDose), dir.path() / "PAT1" / "dose.dcm");
  writeText(dir.file("DICOMDIR"), "an index a real export would hold\n");
  const std::string root = dir.path().string();

  auto listing = listDicomFolder(root);
  ASSERT_TRUE(listing) << listing.message();
  ASSERT_EQ(listing->series.size(), 3u);
  EXPECT_EQ(listing->otherFiles, 1u);  // DICOMDIR
  uint64_t ctSeries = 0;
  for (const DicomSeriesSummary& s : listing->series) {
    EXPECT_TRUE(s.problem.empty()) << s.problem;
    if (s.modality == "CT") {
      ++ctSeries;
      EXPECT_EQ(s.files, 93u);
      EXPECT_EQ(s.dims, (std::array<uint32_t, 3>{64, 64, 93}));
    } else {
      EXPECT_EQ(s.modality, "RTDOSE");
      EXPECT_EQ(s.frames, 15u);
    }
  }
  EXPECT_EQ(ctSeries, 2u);

  expectError(openVolume(root), ErrorCode::kUnsupported,
              {"holds 3 series", "--series", "1.2.3.4.5", "RTDOSE"});
  OpenOptions byUid;
  byUid.dicomSeries = "1.2.3.4.5";
  auto picked = openOrDie(root, byUid);
  ASSERT_TRUE(picked);
  EXPECT_EQ(picked->info().dims[2], 93u);
  EXPECT_TRUE(hasNote(picked->info(), "1 non-DICOM files")) << notesOf(picked->info());
  for (size_t i = 0; i < listing->series.size(); ++i) {
    OpenOptions byIndex;
    byIndex.dicomSeries = std::to_string(i + 1);
    auto source = openOrDie(root, byIndex);
    ASSERT_TRUE(source);
    EXPECT_EQ(source->info().dims, listing->series[i].dims);
  }
  OpenOptions wrong;
  wrong.dicomSeries = "4";
  expectError(openVolume(root, wrong), ErrorCode::kInvalidArgument,
              {"--series 4", "no such series"});
}

TEST(DicomFolders, ImagesWithoutPositionsAreReadWithANote) {
  VOXLINK_REQUIRE_DATA(kSeries);
  TempDir dir;
  copySeries(dir.path(), [](const std::string&, gdcm::DataSet& ds) {
    ds.Remove(gdcm::Tag(0x0020, 0x0032));
    ds.Replace(text(0x0018, 0x0088, gdcm::VR::DS, "2.5"));
  });
  auto source = openOrDie(dir.path().string());
  ASSERT_TRUE(source);
  const VolumeInfo& info = source->info();
  EXPECT_EQ(info.dims, (std::array<uint32_t, 3>{64, 64, 93}));
  EXPECT_EQ(info.origin, (std::array<double, 3>{0, 0, 0}));
  EXPECT_NEAR(info.spacing[2], 2.5, 1e-12);
  EXPECT_TRUE(hasNote(info, "without ImagePositionPatient (0020,0032): origin 0")) << notesOf(info);
  EXPECT_TRUE(hasNote(info, "SpacingBetweenSlices")) << notesOf(info);
  // InstanceNumber order is file order here: the series itself, slice for slice.
  auto series = openOrDie(dataPath(kSeries));
  EXPECT_EQ(readAll(*source).value(), readAll(*series).value());

  // One image alone: a 64x64x1 volume, z spacing from SliceThickness (1.5 in these files).
  TempDir one;
  fs::copy_file(dir.file("CTHead1.dcm"), one.file("CTHead1.dcm"));
  gdcm::Reader reader;
  reader.SetFileName(one.file("CTHead1.dcm").c_str());
  ASSERT_TRUE(reader.Read());
  reader.GetFile().GetDataSet().Remove(gdcm::Tag(0x0018, 0x0088));
  gdcm::Writer writer;
  writer.SetFileName(one.file("CTHead1.dcm").c_str());
  writer.SetFile(reader.GetFile());
  ASSERT_TRUE(writer.Write());
  auto single = openOrDie(one.file("CTHead1.dcm"));
  ASSERT_TRUE(single);
  EXPECT_EQ(single->info().dims, (std::array<uint32_t, 3>{64, 64, 1}));
  EXPECT_NEAR(single->info().spacing[2], 1.5, 1e-12);
  EXPECT_TRUE(hasNote(single->info(), "a single image without ImagePositionPatient"))
      << notesOf(single->info());
}

TEST(DicomFolders, GantryTiltIsRefusedWithTheNumbers) {
  VOXLINK_REQUIRE_DATA(kSeries);
  TempDir dir;
  copySeries(dir.path(), [](const std::string& name, gdcm::DataSet& ds) {
    // CTHead<n> lies at z = 1.5 (n - 1); shift it 0.5 mm in y per slice.
    const int n = std::stoi(name.substr(6));
    ds.Replace(text(0x0020, 0x0032, gdcm::VR::DS, cat("0\\", 0.5 * (n - 1), "\\", 1.5 * (n - 1))));
  });
  expectError(openVolume(dir.path().string()), ErrorCode::kUnsupported,
              {"ImagePositionPatient", "across the slice plane", "gantry tilt of 18.43"});
}

}  // namespace
}  // namespace voxlink::sources::testing
