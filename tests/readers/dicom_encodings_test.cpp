// SPDX-License-Identifier: BSD-3-Clause
// DICOM encodings that other libraries read differently from what voxlink did: 32-bit
// big-endian frames, signed pixels in JPEG-LS and JPEG 2000, deflated files, an RT Dose of one
// frame; and files refused from their header before GDCM decodes (or aborts on) them: HTJ2K,
// 1-bit, color. make_dicom_cases.py builds the files from the real data with pydicom and
// gdcmconv, and writes the values each holds as pydicom and numpy compute them, not voxlink.
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <cstring>
#include <memory>

#include "sources/readers/dicom_reader.h"
#include "tests/readers/reader_test_util.h"

namespace voxlink::sources::testing {

namespace {

constexpr const char* kHead = "ct/slicer_CTHeadAxialDicom/CTHead1.dcm";
constexpr const char* kDose = "dicom_multiframe/pydicom_rtdose.dcm";

class DicomEncodings : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    if (!std::filesystem::exists(dataPath(kHead)) || !std::filesystem::exists(dataPath(kDose)))
      return;
    cases_ = std::make_unique<TempDir>();
    const std::string command =
        cat("'", VOXLINK_PYTHON, "' -W ignore '", VOXLINK_DICOM_CASES_SCRIPT, "' '",
            cases_->path().string(), "' '", ::voxlink::testing::dataDir(), "'");
    generated_ = std::system(command.c_str()) == 0;
  }
  static void TearDownTestSuite() { cases_.reset(); }

  void SetUp() override {
    VOXLINK_REQUIRE_DATA(kHead);
    VOXLINK_REQUIRE_DATA(kDose);
    ASSERT_TRUE(generated_) << "make_dicom_cases.py failed: it needs python3-pydicom, "
                               "python3-numpy and gdcmconv (scripts/install-deps.sh)";
  }

  static std::string file(const std::string& name) { return cases_->file(name + ".dcm"); }

  // Every voxel of CASE.dcm against CASE.f64; returns the source for further checks.
  static std::unique_ptr<VolumeSource> expectValues(const std::string& name) {
    auto source = openOrDie(file(name));
    if (!source) return nullptr;
    const auto bytes = readBytes(cases_->file(name + ".f64"));
    std::vector<double> expected(bytes.size() / 8);
    std::memcpy(expected.data(), bytes.data(), bytes.size());
    auto data = readAll(*source);
    EXPECT_TRUE(data) << data.message();
    if (!data) return source;
    const ScalarType type = source->info().type;
    const size_t size = scalarSize(type);
    EXPECT_EQ(data->size(), expected.size() * size) << name;
    if (data->size() != expected.size() * size) return source;
    size_t wrong = 0, first = 0;
    double got0 = 0;
    for (size_t i = 0; i < expected.size(); ++i) {
      const double got = dispatchScalar(type, [&](auto zero) {
        decltype(zero) v;
        std::memcpy(&v, data->data() + i * size, size);
        return static_cast<double>(v);
      });
      if (got != expected[i] && wrong++ == 0) {
        first = i;
        got0 = got;
      }
    }
    EXPECT_EQ(wrong, 0u) << name << ": " << wrong << " of " << expected.size()
                         << " voxels differ; voxel " << first << " is " << got0 << ", expected "
                         << expected[first];
    return source;
  }

  static inline std::unique_ptr<TempDir> cases_;
  static inline bool generated_ = false;
};

TEST_F(DicomEncodings, BigEndianPixelsAreTheLittleEndianValues) {
  // 32-bit RT Dose frames came out byte-reversed (0.73..4175 Gy instead of 0.795..1.254).
  auto dose = expectValues("dose_big_endian");
  ASSERT_TRUE(dose);
  EXPECT_EQ(dose->info().dims, (std::array<uint32_t, 3>{10, 10, 15}));
  expectValues("dose_one_frame_big_endian");
  expectValues("head_big_endian");
}

TEST_F(DicomEncodings, SignedPixelsInJpegLsAndJpeg2000AreSignExtended) {
  // -2073 in 15 bits came out as 30695: the codestreams hold the bits unsigned.
  for (const char* bits : {"12", "15"}) {
    expectValues(cat("signed", bits, "_raw"));
    for (const char* codec : {"jpegls", "j2k"}) {
      auto source = expectValues(cat("signed", bits, "_", codec));
      ASSERT_TRUE(source);
      EXPECT_EQ(source->info().type, ScalarType::kI16);
      EXPECT_TRUE(hasNote(source->info(), cat("sign-extended from BitsStored ", bits)))
          << notesOf(source->info());
    }
  }
}

TEST_F(DicomEncodings, DeflatedFilesAreRead) {
  // Refused with "holds 207 bytes of pixel data": the size check counted deflated bytes.
  expectValues("head_deflated");
  auto dose = expectValues("dose_deflated");
  ASSERT_TRUE(dose);
  EXPECT_EQ(readInSlabs(*dose, 4), readAll(*dose).value());
}

TEST_F(DicomEncodings, RtDoseOfOneFrameWithoutNumberOfFramesIsRead) {
  // GDCM's image reader aborts on it; the pixel data alone is read.
  expectValues("dose_one_frame");
}

TEST_F(DicomEncodings, ModalityLutSequenceIsNotedNotApplied) {
  auto source = expectValues("modality_lut");
  ASSERT_TRUE(source);
  EXPECT_TRUE(hasNote(source->info(), "Modality LUT Sequence (0028,3000) not applied"))
      << notesOf(source->info());
}

TEST_F(DicomEncodings, UnreadableEncodingsAreRefusedNamingWhatIsUnsupported) {
  // These made GDCM abort and the message said "damaged or not DICOM".
  expectError(openVolume(file("seg_1bit")), ErrorCode::kUnsupported,
              {"seg_1bit.dcm", "tag BitsAllocated (0028,0100): 1", "segmentation"});
  expectError(openVolume(file("htj2k")), ErrorCode::kUnsupported,
              {"htj2k.dcm", "tag TransferSyntaxUID (0002,0010)", "High-Throughput JPEG 2000",
               "1.2.840.10008.1.2.4.201", "not supported"});
  expectError(openVolume(file("rgb_jpeg")), ErrorCode::kUnsupported,
              {"rgb_jpeg.dcm", "tag SamplesPerPixel (0028,0002): 3", "RGB"});
}

// The largest resident size of a child process that opens `path`; exits 0 when the open failed
// with `fragment` in the message.
long childPeakKilobytes(const std::string& path, const std::string& fragment, int& status) {
  const pid_t pid = fork();
  if (pid == 0) {
    auto opened = openVolume(path);
    _exit(!opened && opened.message().find(fragment) != std::string::npos ? 0 : 1);
  }
  rusage usage{};
  if (pid < 0 || wait4(pid, &status, 0, &usage) != pid) return -1;
  return usage.ru_maxrss;  // includes the children it waited for (GDCM's probe)
}

TEST_F(DicomEncodings, ColorIsRefusedBeforeAnyPixelIsDecoded) {
  // A 6 KB JPEG whose header says 12000 x 12000 RGB: decoding would take a 432 MB buffer first
  // (a 4 KB RGB JPEG took 15 s and 1.3 GB before its refusal).
  int status = 0;
  const long kb =
      childPeakKilobytes(file("rgb_jpeg_large"), "SamplesPerPixel (0028,0002): 3", status);
  ASSERT_GT(kb, 0);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << "status " << status;
  EXPECT_LT(kb, 200 * 1024) << "peak resident size of the refusal";
}

}  // namespace
}  // namespace voxlink::sources::testing
