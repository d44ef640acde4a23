// SPDX-License-Identifier: BSD-3-Clause
// Image stacks: slices of real volumes written here with OpenImageIO (PNG files with unpadded
// numbers, a multi-page 16-bit TIFF) must read back identical.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <filesystem>

#include "tests/readers/reader_test_util.h"

namespace voxlink::sources::testing {

namespace {

using OIIO::ImageOutput;
using OIIO::ImageSpec;
using OIIO::TypeDesc;

void writeImage(const std::string& path, int w, int h, int channels, TypeDesc type,
                const void* pixels) {
  auto out = ImageOutput::create(path);
  ASSERT_TRUE(out) << OIIO::geterror();
  ASSERT_TRUE(out->open(path, ImageSpec(w, h, channels, type))) << out->geterror();
  ASSERT_TRUE(out->write_image(type, pixels)) << out->geterror();
  ASSERT_TRUE(out->close());
}

constexpr int kToothX = 103, kToothY = 94, kToothZ = 161;

TEST(ImageStackReader, PngFolderWithUnpaddedNumbersReadsBackTheTooth) {
  VOXLINK_REQUIRE_DATA("ct/tooth_103x94x161_uint8.raw");
  const auto tooth = readBytes(dataPath("ct/tooth_103x94x161_uint8.raw"));
  ASSERT_EQ(tooth.size(), size_t{kToothX} * kToothY * kToothZ);
  TempDir dir;
  const size_t slice = size_t{kToothX} * kToothY;
  for (int z = 0; z < kToothZ; ++z)
    writeImage(dir.file(cat("tooth_", z + 1, ".png")), kToothX, kToothY, 1, TypeDesc::UINT8,
               tooth.data() + z * slice);
  auto source = openOrDie(dir.path().string());
  ASSERT_TRUE(source);
  const VolumeInfo& info = source->info();
  EXPECT_EQ(info.format, "image-stack");
  EXPECT_EQ(info.dims, (std::array<uint32_t, 3>{kToothX, kToothY, kToothZ}));
  EXPECT_EQ(info.type, ScalarType::kU8);
  EXPECT_TRUE(hasNote(info, "tooth_1.png first")) << notesOf(info);
  auto data = readAll(*source);
  ASSERT_TRUE(data) << data.message();
  EXPECT_TRUE(*data == tooth);
  // Random access: slice 99 is tooth_100.png.
  std::vector<uint8_t> one(slice);
  ASSERT_TRUE(source->read(99, 1, one.data()).isOk());
  EXPECT_TRUE(std::equal(one.begin(), one.end(), tooth.begin() + 99 * static_cast<long>(slice)));
}

TEST(ImageStackReader, MultiPageUint16TiffReadsBackTheWalnut) {
  VOXLINK_REQUIRE_DATA("ct/voreen_walnut/walnut.raw");
  const auto walnut = readBytes(dataPath("ct/voreen_walnut/walnut.raw"));
  constexpr int x = 128, y = 96, z = 114;
  ASSERT_EQ(walnut.size(), size_t{x} * y * z * 2);
  TempDir dir;
  const std::string path = dir.file("walnut.tif");
  auto out = ImageOutput::create(path);
  ASSERT_TRUE(out);
  ASSERT_TRUE(out->supports("multiimage"));
  const ImageSpec spec(x, y, 1, TypeDesc::UINT16);
  for (int page = 0; page < z; ++page) {
    ASSERT_TRUE(
        out->open(path, spec, page == 0 ? ImageOutput::Create : ImageOutput::AppendSubimage))
        << out->geterror();
    ASSERT_TRUE(
        out->write_image(TypeDesc::UINT16, walnut.data() + static_cast<size_t>(page) * x * y * 2))
        << out->geterror();
  }
  ASSERT_TRUE(out->close());
  auto source = openOrDie(path);
  ASSERT_TRUE(source);
  EXPECT_EQ(source->info().dims, (std::array<uint32_t, 3>{x, y, z}));
  EXPECT_EQ(source->info().type, ScalarType::kU16);
  auto data = readAll(*source);
  ASSERT_TRUE(data) << data.message();
  EXPECT_TRUE(*data == walnut);
}

TEST(ImageStackReader, RgbSlicesServeChannelZeroWithANote) {
  TempDir dir;
  const auto gray = patternBytes(8 * 6 * 3, 31);
  for (int z = 0; z < 3; ++z) {
    std::vector<uint8_t> rgb(8 * 6 * 3);
    for (int i = 0; i < 48; ++i) {
      rgb[3 * i] = gray[z * 48 + i];
      rgb[3 * i + 1] = 7;
      rgb[3 * i + 2] = 200;
    }
    writeImage(dir.file(cat("c", z, ".png")), 8, 6, 3, TypeDesc::UINT8, rgb.data());
  }
  auto source = openOrDie(dir.path().string());
  ASSERT_TRUE(source);
  EXPECT_TRUE(hasNote(source->info(), "3 channels; channel 0")) << notesOf(source->info());
  auto data = readAll(*source);
  ASSERT_TRUE(data) << data.message();
  EXPECT_TRUE(*data == gray);
}

TEST(ImageStackReader, SlicesOfDifferentSizesAreRefusedNamingTheFile) {
  TempDir dir;
  const auto pixels = patternBytes(10 * 10, 3);
  writeImage(dir.file("s1.png"), 10, 10, 1, TypeDesc::UINT8, pixels.data());
  writeImage(dir.file("s2.png"), 10, 10, 1, TypeDesc::UINT8, pixels.data());
  writeImage(dir.file("s3.png"), 5, 10, 1, TypeDesc::UINT8, pixels.data());
  expectError(openVolume(dir.path().string()), ErrorCode::kSizeMismatch,
              {"s3.png", "image size", "5x10", "10x10", "s1.png"});
}

// A 65-byte PNG whose header claims 60000 x 60000 x 16 bit (no pixel data): refused at open,
// before the converter allocated a 7.2 GB slab for it.
TEST(ImageStackReader, PngTooSmallForItsClaimedSizeIsRefusedAtOpen) {
  TempDir dir;
  const std::vector<uint8_t> png = {
      0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a, 0x00, 0x00, 0x00, 0x0d, 0x49,
      0x48, 0x44, 0x52, 0x00, 0x00, 0xea, 0x60, 0x00, 0x00, 0xea, 0x60, 0x10, 0x00,
      0x00, 0x00, 0x00, 0xf5, 0x29, 0xf6, 0xdd, 0x00, 0x00, 0x00, 0x08, 0x49, 0x44,
      0x41, 0x54, 0x78, 0x9c, 0x03, 0x00, 0x00, 0x00, 0x00, 0x01, 0x48, 0x06, 0x89,
      0xd2, 0x00, 0x00, 0x00, 0x00, 0x49, 0x45, 0x4e, 0x44, 0xae, 0x42, 0x60, 0x82};
  voxlink::testing::writeBytes(dir.file("s0.png"), png);
  voxlink::testing::writeBytes(dir.file("s1.png"), png);
  expectError(openVolume(dir.path().string()), ErrorCode::kTruncated,
              {"s0.png", "image size 60000x60000 needs 7200000000 bytes",
               "a PNG of 65 bytes cannot hold them"});
}

TEST(ImageStackReader, OnePageTiffIsNotAVolume) {
  TempDir dir;
  const auto pixels = patternBytes(4 * 4, 3);
  writeImage(dir.file("one.tif"), 4, 4, 1, TypeDesc::UINT8, pixels.data());
  expectError(openVolume(dir.file("one.tif")), ErrorCode::kUnsupported, {"one.tif", "one page"});
}

}  // namespace
}  // namespace voxlink::sources::testing
