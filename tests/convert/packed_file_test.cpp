// SPDX-License-Identifier: BSD-3-Clause
// Packed files (pack/packed_file.h) on converted real CT: they unpack to the original bytes,
// are much smaller, files packed by earlier builds still unpack, and the sections packing leaves
// out (row starts, brick voxel bases) follow from the masks.
#include "pack/packed_file.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "convert/converter.h"
#include "format/derived_sections.h"
#include "format/validator.h"
#include "pack/open_file.h"
#include "sources/volume_source.h"
#include "tests/convert/packed_fixtures.h"
#include "tests/support/test_util.h"

namespace voxlink::pack {
namespace {

using format::Axis;
using format::deriveBrickVoxelBase;
using format::deriveRowStarts;
using format::rowStartsMatch;
using format::SectionId;
using format::sectionName;
using format::validateFile;
using test::convertReal;
using test::kCarp;
using test::kFoot;
using test::Packed;
using test::packedEntry;
using test::packReal;
using test::TempDir;
using test::unpacked;

TEST(PackedFile, RealCtUnpacksToTheSameBytesAndIsSmaller) {
  VOXLINK_REQUIRE_DATA(kFoot);
  VOXLINK_REQUIRE_DATA(kCarp);
  TempDir dir;
  struct Case {
    const char* data;
    const char* threshold;
    const char* valueType;
  };
  for (const Case& c : {Case{kFoot, "60", nullptr}, Case{kCarp, "1250", nullptr},
                        Case{kCarp, "1250", "f16"}, Case{kCarp, "1250", "f32"}}) {
    SCOPED_TRACE(std::string(c.data) + (c.valueType ? c.valueType : ""));
    const std::string path = convertReal(dir, c.data, c.threshold, c.valueType);
    uint64_t sizes[2] = {0, 0};
    for (bool predict : {true, false}) {
      const Packed p = packReal(dir, path, predict);
      EXPECT_EQ(unpacked(p.packed), p.original);
      EXPECT_LT(p.packed.size(), p.original.size() * 0.9)
          << p.packed.size() << " of " << p.original.size();
      sizes[predict] = p.packed.size();
      // Every reader opens it: open() unpacks, the validator accepts what comes out.
      auto opened = pack::openValidatedFile(dir.file("packed.vxl"));
      ASSERT_TRUE(opened) << opened.message();
      EXPECT_EQ(opened->packedBytes(), p.packed.size());
    }
    // Predicted gradients cost less than delta-coded ones (the thin carp's voxels are mostly
    // surface, where the prediction guesses: there it saves about 12 %).
    EXPECT_LT(sizes[1], sizes[0]) << sizes[1] << " predicted, " << sizes[0] << " not";
  }
}

// Packing predicts GRAD a chunk at a time, unpacking the whole section at once: a GRAD of several
// chunks (the foot at a low threshold: 4.7 million entries, three chunks) unpacks to its bytes
// only if every chunk's predictions are the whole section's, for small and large bricks.
TEST(PackedFile, GradientsOfSeveralChunksUnpackToTheSameBytes) {
  VOXLINK_REQUIRE_DATA(kFoot);
  TempDir dir;
  for (uint32_t brick : {8u, 32u}) {
    SCOPED_TRACE("brick " + std::to_string(brick));
    const std::string path = convertReal(dir, kFoot, "5", nullptr, brick, Axis::kY);
    auto file = pack::openValidatedFile(path);
    ASSERT_TRUE(file) << file.message();
    ASSERT_GT(file->gradientCodes().size_bytes(), 2 * kPackChunkBytes);  // three chunks or more
    const Packed p = packReal(dir, path);
    EXPECT_EQ(unpacked(p.packed), p.original);
  }
}

// The gradient prediction is part of the packed format: files packed by earlier builds
// (tests/data/packed: v1 with the float64 prediction, v2 with the portable one and derived row
// starts) must still unpack, which they only do when this build predicts the same codes (GRAD's
// original checksum is checked after the prediction is added back).
TEST(PackedFile, FilesPackedByEarlierBuildsStillUnpack) {
  for (const char* version : {"v1", "v2"})
    for (const char* name : {"u8_b8_z", "u16_b4_x", "f32_b16_y", "f32_u8_scaled", "scene"}) {
      SCOPED_TRACE(std::string(version) + "/" + name);
      const std::string path =
          std::string(VOXLINK_PACKED_DIR) + "/" + version + "/" + name + ".packed.vxl";
      const std::vector<uint8_t> packed = testing::readBytes(path);
      ASSERT_FALSE(packed.empty()) << path;
      for (unsigned threads : {1u, 2u}) {
        auto file = unpackFile(packed, path, uint64_t{1} << 28, threads);
        ASSERT_TRUE(file) << file.message();
        const auto report = validateFile(*file);
        EXPECT_TRUE(report) << report.message();
      }
    }
}

TEST(PackedFile, PackingRefusesItsInputAsOutput) {
  VOXLINK_REQUIRE_DATA(kFoot);
  TempDir dir;
  const std::string path = convertReal(dir, kFoot, "60");
  auto file = pack::openValidatedFile(path);
  ASSERT_TRUE(file);
  auto report = packFile(*file, path);
  ASSERT_FALSE(report);
  EXPECT_NE(report.message().find(path), std::string::npos) << report.message();
  EXPECT_EQ(testing::readBytes(path).size(), file->fileBytes());
}

TEST(PackedFile, RowStartsAndBrickBasesFollowFromTheMasks) {
  VOXLINK_REQUIRE_DATA(kCarp);
  TempDir dir;
  for (const char* brick : {"4", "16", "32"}) {
    SCOPED_TRACE(brick);
    auto source = sources::openVolume(testing::dataPath(kCarp), {});
    ASSERT_TRUE(source) << source.message();
    convert::ConvertOptions options;
    options.classification = convert::thresholdClassification({"1250"}).value();
    options.brickSize = static_cast<uint32_t>(std::stoul(brick));
    const std::string path = dir.file(std::string("b") + brick + ".vxl");
    ASSERT_TRUE(convert::convertVolume(**source, options, path));
    auto file = pack::openValidatedFile(path);
    ASSERT_TRUE(file) << file.message();
    const uint32_t n = file->header().brickSize;
    const auto masks = file->sectionBytes(SectionId::kRowMask);
    for (SectionId id : {SectionId::kRowStart, SectionId::kBrickVoxelBase}) {
      const auto stored = file->sectionBytes(id);
      std::vector<uint8_t> derived(stored.size(), 0xAB);
      const Status s = id == SectionId::kRowStart ? deriveRowStarts(masks, n, derived, "t")
                                                  : deriveBrickVoxelBase(masks, n, derived, "t");
      ASSERT_TRUE(s.isOk()) << s.message();
      EXPECT_TRUE(std::equal(derived.begin(), derived.end(), stored.begin())) << sectionName(id);
      // A size that does not fit the masks' bricks is refused, naming what was derived.
      const size_t oneMore = id == SectionId::kRowStart ? size_t{2} * n * n : 4;
      std::vector<uint8_t> longer(stored.size() + oneMore);
      const Status wrong = id == SectionId::kRowStart
                               ? deriveRowStarts(masks, n, longer, "f.vxl: ROWS")
                               : deriveBrickVoxelBase(masks, n, longer, "f.vxl: BVOX");
      ASSERT_FALSE(wrong.isOk());
      EXPECT_NE(wrong.message().find("derived from MASK"), std::string::npos) << wrong.message();
      if (id == SectionId::kRowStart) {  // the check packing makes, a range of bricks at a time
        EXPECT_TRUE(rowStartsMatch(masks, n, stored));
        std::vector<uint8_t> changed(stored.begin(), stored.end());
        changed[changed.size() - 2] ^= 1;  // the last brick's last row
        EXPECT_FALSE(rowStartsMatch(masks, n, changed));
        EXPECT_FALSE(rowStartsMatch(masks, n, longer));
      }
    }
    // Packing stores neither.
    const Packed p = packReal(dir, path);
    EXPECT_EQ(unpacked(p.packed), p.original);
    for (SectionId id : {SectionId::kRowStart, SectionId::kBrickVoxelBase})
      EXPECT_EQ(packedEntry(p.packed, id).bytes, 0u) << sectionName(id);
  }
}

}  // namespace
}  // namespace voxlink::pack
