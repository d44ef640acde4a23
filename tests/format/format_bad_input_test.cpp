// SPDX-License-Identifier: BSD-3-Clause
// Damaged and hostile files: each gives the exact error code and a message naming the field.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>

#include "base/crc32c.h"
#include "format/bricked_volume.h"
#include "format/gradient_codec.h"
#include "format/validator.h"
#include "format/voxlink_file.h"
#include "pack/open_file.h"
#include "tests/support/test_util.h"

namespace voxlink::format {
namespace {

class FormatBadInput : public ::testing::Test {
 protected:
  void SetUp() override {
    VolumeDescription d;
    d.dims = {20, 20, 20};
    BrickedVolumeBuilder builder(d);
    for (uint32_t i = 0; i < 20; ++i) builder.add(i, i, i, 100 + i, encodeGradient(1.0, 1.0, 1.0));
    auto volume = builder.build(R"({"ok":true})");
    ASSERT_TRUE(volume);
    path_ = dir_.file("good.vxl");
    ASSERT_TRUE(writeBrickedVolume(path_, *volume).isOk());
    bytes_ = testing::readBytes(path_);
  }

  FileHeader& header() { return *reinterpret_cast<FileHeader*>(bytes_.data()); }
  void resealHeader() {
    header().headerCrc = 0;
    header().headerCrc = crc32c(bytes_.data(), sizeof(FileHeader));
  }
  SectionEntry* entry(SectionId id) {
    auto* table = reinterpret_cast<SectionEntry*>(bytes_.data() + header().sectionTableOffset);
    for (uint32_t i = 0; i < header().sectionCount; ++i)
      if (table[i].id == static_cast<uint32_t>(id)) return &table[i];
    return nullptr;
  }
  Result<VoxLinkFile> reopen() { return pack::fileFromBytes(bytes_, "bad.vxl"); }

  testing::TempDir dir_;
  std::string path_;
  std::vector<uint8_t> bytes_;
};

TEST_F(FormatBadInput, GoodFileOpensAndValidates) {
  auto f = reopen();
  ASSERT_TRUE(f) << f.message();
  EXPECT_TRUE(validateFile(*f));
}

// The validator's per-voxel checks (it reads the codes and the u8 values in bulk and only walks
// them one by one to name the first bad one).
TEST_F(FormatBadInput, NonCanonicalGradientIsNamed) {
  for (const uint16_t bad : {uint16_t(0x0005), uint16_t(0xFE01), uint16_t(0xFF00)}) {
    std::vector<uint8_t> good = bytes_;
    SectionEntry* grad = entry(SectionId::kGradients);
    for (const uint64_t voxel : {uint64_t{13}, uint64_t{6}})  // the first one named: 6
      std::memcpy(bytes_.data() + grad->offset + 2 * voxel, &bad, 2);
    grad->crc = crc32c(bytes_.data() + grad->offset, grad->bytes);
    auto f = reopen();
    ASSERT_TRUE(f) << f.message();
    const auto report = validateFile(*f);
    ASSERT_FALSE(report) << std::hex << bad;
    EXPECT_EQ(report.code(), ErrorCode::kCorrupt);
    EXPECT_NE(report.message().find("section GRAD: voxel 6 has the reserved or non-canonical"),
              std::string::npos)
        << report.message();
    bytes_ = good;
  }
}

TEST_F(FormatBadInput, ValueOutsideTheHeadersRangeIsNamed) {
  // The stored values are 100..119; a header that claims less (or more) is refused.
  for (const auto& [lo, hi] : {std::pair{100.0, 110.0}, std::pair{105.0, 119.0}}) {
    std::vector<uint8_t> good = bytes_;
    header().valueMin = lo;
    header().valueMax = hi;
    resealHeader();
    auto f = reopen();
    ASSERT_TRUE(f) << f.message();
    const auto report = validateFile(*f);
    ASSERT_FALSE(report) << lo << " " << hi;
    EXPECT_NE(report.message().find("lies outside header.valueMin/valueMax"), std::string::npos)
        << report.message();
    bytes_ = good;
  }
  // The whole range is accepted.
  auto f = reopen();
  ASSERT_TRUE(f);
  EXPECT_TRUE(validateFile(*f));
}

TEST_F(FormatBadInput, TruncatedAnywhere) {
  for (size_t keep : {size_t{0}, size_t{10}, size_t{255}, bytes_.size() / 2, bytes_.size() - 1}) {
    std::vector<uint8_t> cut(bytes_.begin(), bytes_.begin() + static_cast<long>(keep));
    auto f = pack::fileFromBytes(cut, "cut.vxl");
    ASSERT_FALSE(f) << keep;
    EXPECT_EQ(f.code(), ErrorCode::kTruncated) << keep << ": " << f.message();
    EXPECT_NE(f.message().find("cut.vxl"), std::string::npos);
  }
}

TEST_F(FormatBadInput, WrongMagic) {
  bytes_[0] = 'X';
  auto f = reopen();
  EXPECT_EQ(f.code(), ErrorCode::kNotAVoxLinkFile);
  EXPECT_NE(f.message().find("header.magic"), std::string::npos);
}

TEST_F(FormatBadInput, SwappedByteOrderIsNamed) {
  header().byteOrderMark = kByteOrderMarkSwapped;
  resealHeader();
  auto f = reopen();
  EXPECT_EQ(f.code(), ErrorCode::kByteOrder);
  EXPECT_NE(f.message().find("big-endian"), std::string::npos);
}

TEST_F(FormatBadInput, NewerMajorVersion) {
  header().versionMajor = 3;
  resealHeader();
  auto f = reopen();
  EXPECT_EQ(f.code(), ErrorCode::kUnsupported);
  EXPECT_NE(f.message().find("versionMajor"), std::string::npos);
}

TEST_F(FormatBadInput, NewerMinorVersionIsAccepted) {
  header().versionMinor = 7;
  resealHeader();
  EXPECT_TRUE(reopen());
}

TEST_F(FormatBadInput, HeaderChecksum) {
  header().spacing[0] = 2.0;  // not resealed
  auto f = reopen();
  EXPECT_EQ(f.code(), ErrorCode::kCorrupt);
  EXPECT_NE(f.message().find("header.headerCrc"), std::string::npos);
}

TEST_F(FormatBadInput, HeaderLyingAboutVoxelCount) {
  header().voxelCount += 1;
  resealHeader();
  auto f = reopen();
  EXPECT_EQ(f.code(), ErrorCode::kSizeMismatch) << f.message();
  EXPECT_NE(f.message().find("section VALU.bytes"), std::string::npos) << f.message();
}

TEST_F(FormatBadInput, BadBrickSizeAndDims) {
  header().brickSize = 12;
  resealHeader();
  EXPECT_NE(reopen().message().find("header.brickSize"), std::string::npos);
  SetUp();
  header().dims[1] = 0;
  resealHeader();
  EXPECT_NE(reopen().message().find("header.dims[1]"), std::string::npos);
}

TEST_F(FormatBadInput, SectionPastTheEnd) {
  entry(SectionId::kValues)->offset = bytes_.size() + 64 - bytes_.size() % 64;
  auto f = reopen();
  EXPECT_EQ(f.code(), ErrorCode::kTruncated);
  EXPECT_NE(f.message().find("VALU"), std::string::npos);
}

// Bytes that no section describes are refused: the checksums cover only what the table names, so
// a file (or a packed file's unpacked size) could otherwise carry anything, of any size.
TEST_F(FormatBadInput, BytesThatNoSectionDescribes) {
  const std::vector<uint8_t> good = bytes_;
  bytes_.resize(good.size() + 63, 0);  // less than the alignment: padding
  EXPECT_TRUE(reopen().isOk());
  bytes_.resize(good.size() + 1000, 0);
  auto f = reopen();
  EXPECT_EQ(f.code(), ErrorCode::kCorrupt);
  EXPECT_NE(
      f.message().find("bad.vxl: the last 1000 bytes of the " + std::to_string(good.size() + 1000) +
                       "-byte file belong to no section"),
      std::string::npos)
      << f.message();
  // A gap inside: META moved 128 bytes further (its bytes and checksum moved with it).
  bytes_ = good;
  SectionEntry* meta = entry(SectionId::kMeta);
  const uint64_t from = meta->offset, bytes = meta->bytes;
  bytes_.insert(bytes_.begin() + long(from), 128, 0);
  header().sectionTableOffset += 128;
  resealHeader();
  meta = entry(SectionId::kMeta);
  meta->offset = from + 128;
  ASSERT_EQ(meta->bytes, bytes);
  f = reopen();
  EXPECT_EQ(f.code(), ErrorCode::kCorrupt);
  EXPECT_NE(f.message().find(") belong to no section (more than 63 bytes of padding)"),
            std::string::npos)
      << f.message();
}

TEST_F(FormatBadInput, MissingSection) {
  entry(SectionId::kRowMask)->id = fourCC("XXXX");
  auto f = reopen();
  EXPECT_EQ(f.code(), ErrorCode::kCorrupt);
  EXPECT_NE(f.message().find("MASK: missing"), std::string::npos);
}

TEST_F(FormatBadInput, FlippedPayloadBitFailsItsChecksum) {
  const SectionEntry* e = entry(SectionId::kGradients);
  bytes_[e->offset + 3] ^= 0x10;
  auto f = reopen();
  ASSERT_TRUE(f);  // open() does not read payloads
  auto report = validateFile(*f);
  ASSERT_FALSE(report);
  EXPECT_EQ(report.code(), ErrorCode::kCorrupt);
  EXPECT_NE(report.message().find("section GRAD.crc"), std::string::npos) << report.message();
}

TEST_F(FormatBadInput, InvariantBrokenWithValidChecksum) {
  // A row start that disagrees with the masks, with its checksum recomputed.
  SectionEntry* e = entry(SectionId::kRowStart);
  auto* rows = reinterpret_cast<uint16_t*>(bytes_.data() + e->offset);
  rows[5] += 1;
  e->crc = crc32c(bytes_.data() + e->offset, e->bytes);
  auto f = reopen();
  ASSERT_TRUE(f);
  auto report = validateFile(*f);
  ASSERT_FALSE(report);
  EXPECT_NE(report.message().find("section ROWS"), std::string::npos) << report.message();
}

TEST_F(FormatBadInput, UnwritableOutputLeavesNothing) {
  VolumeDescription d;
  d.dims = {4, 4, 4};
  auto volume = BrickedVolumeBuilder(d).build();
  ASSERT_TRUE(volume);
  const std::string missingDir = dir_.file("no/such/dir/out.vxl");
  Status s = writeBrickedVolume(missingDir, *volume);
  EXPECT_EQ(s.code(), ErrorCode::kIo);
  EXPECT_NE(s.message().find("out.vxl"), std::string::npos);
  EXPECT_EQ(testing::listDir(dir_.path()), std::vector<std::string>{"good.vxl"});
}

}  // namespace
}  // namespace voxlink::format
