// SPDX-License-Identifier: BSD-3-Clause
// NIfTI: the header facts are decoded here by hand (NIfTI-1 field offsets, big-endian file),
// the voxels are the gunzipped bytes after vox_offset; written files test scl_slope/scl_inter.
#include <gtest/gtest.h>

#include <cstring>
#include <limits>

#include "tests/readers/reader_test_util.h"

namespace voxlink::sources::testing {

namespace {

template <class T>
T bigEndianAt(const std::vector<uint8_t>& b, size_t offset) {
  uint8_t tmp[sizeof(T)];
  for (size_t i = 0; i < sizeof(T); ++i) tmp[i] = b[offset + sizeof(T) - 1 - i];
  T v;
  std::memcpy(&v, tmp, sizeof(T));
  return v;
}

TEST(NiftiReader, Avg152BigEndianGzipMatchesHandDecodedHeaderAndBytes) {
  VOXLINK_REQUIRE_DATA("mri/vtk_avg152T1_RL_nifti.nii.gz");
  const std::string path = dataPath("mri/vtk_avg152T1_RL_nifti.nii.gz");
  const auto file = gunzipFile(path);
  ASSERT_GE(file.size(), 352u);
  ASSERT_EQ(bigEndianAt<int32_t>(file, 0),
            348);  // sizeof_hdr read big-endian: the file is MSB first
  const std::array<uint32_t, 3> dims{uint32_t(bigEndianAt<int16_t>(file, 42)),
                                     uint32_t(bigEndianAt<int16_t>(file, 44)),
                                     uint32_t(bigEndianAt<int16_t>(file, 46))};
  const std::array<double, 3> pixdim{bigEndianAt<float>(file, 80), bigEndianAt<float>(file, 84),
                                     bigEndianAt<float>(file, 88)};
  const auto voxOffset = static_cast<size_t>(bigEndianAt<float>(file, 108));
  const std::array<double, 3> translation{bigEndianAt<float>(file, 280 + 12),
                                          bigEndianAt<float>(file, 296 + 12),
                                          bigEndianAt<float>(file, 312 + 12)};
  EXPECT_EQ(bigEndianAt<int16_t>(file, 70), 2);    // DT_UINT8
  EXPECT_EQ(bigEndianAt<int16_t>(file, 254), 4);   // sform_code MNI
  EXPECT_EQ(bigEndianAt<float>(file, 112), 0.0f);  // scl_slope 0: no scaling

  auto source = openOrDie(path);
  ASSERT_TRUE(source);
  const VolumeInfo& info = source->info();
  EXPECT_EQ(info.format, "nifti");
  EXPECT_EQ(info.dims, dims);
  EXPECT_EQ(info.dims, (std::array<uint32_t, 3>{91, 109, 91}));  // README
  EXPECT_EQ(info.type, ScalarType::kU8);
  EXPECT_EQ(info.spacing, pixdim);
  EXPECT_EQ(info.origin, translation);
  EXPECT_TRUE(hasNote(info, "sform")) << notesOf(info);
  auto data = readAll(*source);
  ASSERT_TRUE(data) << data.message();
  ASSERT_EQ(file.size() - voxOffset, data->size());
  EXPECT_TRUE(std::equal(data->begin(), data->end(), file.begin() + static_cast<long>(voxOffset)));
  // Computed outside this project with Python's gzip module: sum(gzip.open(f).read()[352:]).
  uint64_t sum = 0;
  for (uint8_t v : *data) sum += v;
  EXPECT_EQ(sum, 74825382u);
}

// A NIfTI-1 single-file header written field by field (little-endian).
std::vector<uint8_t> niftiHeader(std::array<int16_t, 8> dim, int16_t datatype, int16_t bitpix,
                                 std::array<float, 3> pixdim, float slope, float intercept) {
  std::vector<uint8_t> h(352, 0);
  auto put = [&](size_t at, auto v) { std::memcpy(h.data() + at, &v, sizeof v); };
  put(0, int32_t{348});
  for (int i = 0; i < 8; ++i) put(40 + 2 * i, dim[i]);
  put(70, datatype);
  put(72, bitpix);
  put(76, 1.0f);
  for (int i = 0; i < 3; ++i) put(80 + 4 * i, pixdim[i]);
  put(108, 352.0f);
  put(112, slope);
  put(116, intercept);
  put(123, uint8_t{2});  // mm
  put(254, int16_t{1});  // sform_code scanner
  const float srow[3][4] = {{pixdim[0], 0, 0, -5}, {0, pixdim[1], 0, 6}, {0, 0, pixdim[2], 7}};
  std::memcpy(h.data() + 280, srow, sizeof srow);
  std::memcpy(h.data() + 344, "n+1\0", 4);
  return h;
}

TEST(NiftiReader, SclSlopeInterceptAreAppliedAndTheTypeFollowsThem) {
  TempDir dir;
  const auto raw = patternBytes(4 * 3 * 2 * 2, 21);  // int16 values
  std::vector<uint8_t> file =
      niftiHeader({3, 4, 3, 2, 1, 1, 1, 1}, 4, 16, {0.5f, 0.5f, 2.0f}, 0.5f, -10.0f);
  file.insert(file.end(), raw.begin(), raw.end());
  writeBytes(dir.file("s.nii"), file);
  writeBytes(dir.file("s.nii.gz"), gzipBytes(file));
  for (const char* name : {"s.nii", "s.nii.gz"}) {
    SCOPED_TRACE(name);
    auto source = openOrDie(dir.file(name));
    ASSERT_TRUE(source);
    const VolumeInfo& info = source->info();
    EXPECT_EQ(info.type, ScalarType::kF32);  // a fractional slope gives floats
    EXPECT_EQ(info.spacing, (std::array<double, 3>{0.5, 0.5, 2}));
    EXPECT_EQ(info.origin, (std::array<double, 3>{-5, 6, 7}));
    EXPECT_TRUE(hasNote(info, "scl_slope/scl_inter applied")) << notesOf(info);
    auto data = readAll(*source);
    ASSERT_TRUE(data) << data.message();
    ASSERT_EQ(data->size(), 24u * 4u);
    for (size_t i = 0; i < 24; ++i) {
      int16_t stored;
      std::memcpy(&stored, raw.data() + 2 * i, 2);
      float value;
      std::memcpy(&value, data->data() + 4 * i, 4);
      EXPECT_EQ(value, static_cast<float>(stored * 0.5 - 10.0)) << i;
    }
  }

  // Integral slope and intercept on uint8: exact integers, i16 holds [-1024, -514].
  const auto bytes = patternBytes(4 * 3 * 2, 22);
  std::vector<uint8_t> u8 = niftiHeader({3, 4, 3, 2, 1, 1, 1, 1}, 2, 8, {1, 1, 1}, 2.0f, -1024.0f);
  u8.insert(u8.end(), bytes.begin(), bytes.end());
  writeBytes(dir.file("u.nii"), u8);
  auto source = openOrDie(dir.file("u.nii"));
  ASSERT_TRUE(source);
  EXPECT_EQ(source->info().type, ScalarType::kI16);
  auto data = readAll(*source);
  ASSERT_TRUE(data) << data.message();
  for (size_t i = 0; i < bytes.size(); ++i) {
    int16_t v;
    std::memcpy(&v, data->data() + 2 * i, 2);
    EXPECT_EQ(v, bytes[i] * 2 - 1024) << i;
  }
}

TEST(NiftiReader, RefusesTimeSeriesAndComplexData) {
  TempDir dir;
  std::vector<uint8_t> series = niftiHeader({4, 2, 2, 2, 3, 1, 1, 1}, 2, 8, {1, 1, 1}, 0, 0);
  series.resize(352 + 24);
  writeBytes(dir.file("t.nii"), series);
  expectError(openVolume(dir.file("t.nii")), ErrorCode::kUnsupported, {"t.nii", "dim[4]", "3"});
  std::vector<uint8_t> complex = niftiHeader({3, 2, 2, 2, 1, 1, 1, 1}, 32, 64, {1, 1, 1}, 0, 0);
  complex.resize(352 + 64);
  writeBytes(dir.file("c.nii"), complex);
  expectError(openVolume(dir.file("c.nii")), ErrorCode::kUnsupported, {"c.nii", "datatype", "32"});
}

}  // namespace
}  // namespace voxlink::sources::testing

namespace voxlink::sources::testing {
namespace {

// libnifti turns pixdim 0 and NaN into 1 silently: NaN must be an error naming the field, 0 a
// note, and --spacing takes over from either.
TEST(NiftiReader, PixdimZeroIsANoteAndNaNAnError) {
  TempDir dir;
  const auto raw = patternBytes(4 * 3 * 2, 5);
  auto write = [&](const char* name, std::array<float, 3> pixdim) {
    std::vector<uint8_t> file = niftiHeader({3, 4, 3, 2, 1, 1, 1, 1}, 2, 8, pixdim, 0, 0);
    file.insert(file.end(), raw.begin(), raw.end());
    writeBytes(dir.file(name), file);
  };
  write("nan.nii", {1.0f, std::numeric_limits<float>::quiet_NaN(), 1.0f});
  expectError(openVolume(dir.file("nan.nii")), ErrorCode::kCorrupt,
              {"nan.nii", "'pixdim[2]'", "--spacing"});
  OpenOptions spacing;
  spacing.spacing = std::array<double, 3>{1, 2, 3};
  auto given = openOrDie(dir.file("nan.nii"), spacing);
  ASSERT_TRUE(given);
  EXPECT_EQ(given->info().spacing, (std::array<double, 3>{1, 2, 3}));

  write("zero.nii", {0.0f, 1.0f, 1.0f});
  auto zero = openOrDie(dir.file("zero.nii"));
  ASSERT_TRUE(zero);
  EXPECT_TRUE(hasNote(zero->info(), "'pixdim[1]' is 0")) << notesOf(zero->info());
  EXPECT_EQ(zero->info().spacing[0], 1.0);
}

}  // namespace
}  // namespace voxlink::sources::testing
