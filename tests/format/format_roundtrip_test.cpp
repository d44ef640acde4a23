// SPDX-License-Identifier: BSD-3-Clause
// Round trip of every section: build random sparse volumes, write, read back, compare.
#include <gtest/gtest.h>

#include <cstring>
#include <map>
#include <random>
#include <tuple>

#include "format/bricked_volume.h"
#include "format/gradient_codec.h"
#include "format/half.h"
#include "format/validator.h"
#include "format/voxel_locator.h"
#include "format/voxlink_file.h"
#include "pack/open_file.h"
#include "tests/support/test_util.h"

namespace voxlink::format {
namespace {

using Key = std::tuple<uint32_t, uint32_t, uint32_t>;

struct Case {
  uint32_t brick;
  Axis axis;
  StoredType type;
};

class FormatRoundTrip : public ::testing::TestWithParam<Case> {};

TEST_P(FormatRoundTrip, EverySectionAndVoxelSurvives) {
  const Case c = GetParam();
  std::mt19937 rng(c.brick * 31 + static_cast<int>(c.axis) * 7 + static_cast<int>(c.type));
  VolumeDescription d;
  d.dims = {37, 21, 50};  // not multiples of any brick size
  d.brickSize = c.brick;
  d.predominantAxis = c.axis;
  d.valueType = c.type;
  d.sourceType = ScalarType::kF32;
  d.spacing = {0.5, 1.0, 2.5};
  d.origin = {-3.0, 4.0, 0.25};
  d.valueScale = 0.5;
  d.valueOffset = -10.0;
  BrickedVolumeBuilder builder(d);
  std::map<Key, std::pair<uint32_t, uint16_t>> expected;
  std::uniform_int_distribution<uint32_t> bits(0, c.type == StoredType::kU8 ? 255 : 65535);
  for (int i = 0; i < 4000; ++i) {
    const Key k{rng() % d.dims[0], rng() % d.dims[1], rng() % d.dims[2]};
    if (expected.count(k)) continue;
    uint32_t b = bits(rng);
    if (c.type == StoredType::kF32) {
      const float f = static_cast<float>(b) * 0.25f;
      std::memcpy(&b, &f, 4);
    } else if (c.type == StoredType::kF16) {
      b = floatToHalf(static_cast<float>(b % 2000) * 0.5f);  // finite halves only
    }
    const uint16_t g =
        encodeGradient(float(rng() % 200) - 100.0f, float(rng() % 200) - 100.0f, 1.0f);
    expected[k] = {b, g};
    builder.add(std::get<0>(k), std::get<1>(k), std::get<2>(k), b, g);
  }
  auto volume = builder.build(R"({"test":"roundtrip"})");
  ASSERT_TRUE(volume) << volume.message();

  testing::TempDir dir;
  const std::string path = dir.file("roundtrip.vxl");
  ASSERT_TRUE(writeBrickedVolume(path, *volume).isOk());
  auto file = pack::openFile(path);
  ASSERT_TRUE(file) << file.message();
  auto report = validateFile(*file);
  ASSERT_TRUE(report) << report.message();
  EXPECT_EQ(report->voxelsChecked, expected.size());

  // Sections are byte-identical to what was built.
  auto same = [&](SectionId id, const void* data, size_t bytes) {
    auto s = file->sectionBytes(id);
    ASSERT_GE(s.size(), bytes);
    EXPECT_EQ(std::memcmp(s.data(), data, bytes), 0) << sectionName(id);
  };
  same(SectionId::kBrickOccupancy, volume->occupancy.data(), volume->occupancy.size() * 4);
  same(SectionId::kBrickRank, volume->rank.data(), volume->rank.size() * 4);
  same(SectionId::kBrickVoxelBase, volume->voxelBase.data(), volume->voxelBase.size() * 4);
  same(SectionId::kRowStart, volume->rowStarts.data(), volume->rowStarts.size() * 2);
  same(SectionId::kRowMask, volume->rowMasks.data(), volume->rowMasks.size() * 4);
  same(SectionId::kValues, volume->values.data(), volume->values.size());
  same(SectionId::kGradients, volume->gradients.data(), volume->gradients.size() * 2);
  EXPECT_EQ(file->metaJson(), R"({"test":"roundtrip"})");
  EXPECT_EQ(file->header().spacing[2], 2.5);
  EXPECT_EQ(file->header().origin[0], -3.0);

  // Every voxel is found where it was put, and nowhere else.
  VoxelLocator locator(*file);
  const size_t valueSize = storedSize(c.type);
  uint64_t visited = 0;
  locator.forEachVoxel([&](uint32_t x, uint32_t y, uint32_t z, uint64_t index) {
    auto it = expected.find({x, y, z});
    ASSERT_NE(it, expected.end());
    uint32_t b = 0;
    std::memcpy(&b, file->valueBytes() + index * valueSize, valueSize);
    EXPECT_EQ(b, it->second.first);
    EXPECT_EQ(file->gradientCodes()[index], it->second.second);
    EXPECT_EQ(locator.find(x, y, z), static_cast<int64_t>(index));
    ++visited;
  });
  EXPECT_EQ(visited, expected.size());
  int misses = 0;
  for (uint32_t z = 0; z < d.dims[2]; ++z)
    for (uint32_t y = 0; y < d.dims[1]; ++y)
      for (uint32_t x = 0; x < d.dims[0]; ++x)
        if (!expected.count({x, y, z})) misses += locator.find(x, y, z) < 0;
  EXPECT_EQ(misses, int(d.dims[0] * d.dims[1] * d.dims[2] - expected.size()));
}

INSTANTIATE_TEST_SUITE_P(
    BrickSizesAxesTypes, FormatRoundTrip,
    ::testing::Values(Case{4, Axis::kZ, StoredType::kU8}, Case{8, Axis::kX, StoredType::kU16},
                      Case{16, Axis::kY, StoredType::kF32}, Case{32, Axis::kZ, StoredType::kF16},
                      Case{8, Axis::kZ, StoredType::kU8}, Case{32, Axis::kX, StoredType::kU8}));

TEST(FormatRoundTrip, EmptyVolumeIsAValidFile) {
  VolumeDescription d;
  d.dims = {10, 10, 10};
  auto volume = BrickedVolumeBuilder(d).build();
  ASSERT_TRUE(volume);
  testing::TempDir dir;
  ASSERT_TRUE(writeBrickedVolume(dir.file("empty.vxl"), *volume).isOk());
  auto file = pack::openFile(dir.file("empty.vxl"));
  ASSERT_TRUE(file) << file.message();
  EXPECT_EQ(file->voxelCount(), 0u);
  EXPECT_TRUE(validateFile(*file));
}

TEST(FormatRoundTrip, FullyOccupiedVolume) {
  VolumeDescription d;
  d.dims = {17, 8, 9};
  d.brickSize = 8;
  BrickedVolumeBuilder builder(d);
  for (uint32_t z = 0; z < 9; ++z)
    for (uint32_t y = 0; y < 8; ++y)
      for (uint32_t x = 0; x < 17; ++x)
        builder.add(x, y, z, (x + y + z) & 255, encodeGradient(1.0, 0.0, 0.0));
  auto volume = builder.build();
  ASSERT_TRUE(volume);
  testing::TempDir dir;
  ASSERT_TRUE(writeBrickedVolume(dir.file("full.vxl"), *volume).isOk());
  auto file = pack::openFile(dir.file("full.vxl"));
  ASSERT_TRUE(file);
  EXPECT_TRUE(validateFile(*file));
  EXPECT_EQ(file->voxelCount(), 17u * 8 * 9);
  EXPECT_EQ(file->occupiedBrickCount(), 3u * 1 * 2);
  VoxelLocator locator(*file);
  EXPECT_EQ(file->value(static_cast<uint64_t>(locator.find(16, 7, 8))), double((16 + 7 + 8) & 255));
}

// Checksums come from the writes themselves when a section arrives front to back, and from
// reading the file back otherwise; both must give the same file.
TEST(FormatRoundTrip, ChecksumsDoNotDependOnWriteOrder) {
  VolumeDescription d;
  d.dims = {40, 30, 20};
  BrickedVolumeBuilder builder(d);
  std::mt19937 rng(5);
  for (uint32_t z = 0; z < 20; ++z)
    for (uint32_t y = 0; y < 30; ++y)
      for (uint32_t x = 0; x < 40; ++x)
        if (rng() % 8 == 0)
          builder.add(x, y, z, rng() & 255,
                      encodeGradient(float(rng() % 9) - 4.0f, float(rng() % 9) - 4.0f, 1.0f));
  auto volume = builder.build(R"({"test":"order"})");
  ASSERT_TRUE(volume) << volume.message();
  testing::TempDir dir;
  ASSERT_TRUE(writeBrickedVolume(dir.file("in_order.vxl"), *volume).isOk());

  const BrickedVolume& v = *volume;
  const FileHeader header = makeHeader(v.description, v.voxelCount(), v.occupiedBrickCount());
  auto writer = FileWriter::create(dir.file("shuffled.vxl"), header);
  ASSERT_TRUE(writer) << writer.message();
  // Each section in three chunks, last chunk first; the values section twice over.
  auto backwards = [&](SectionId id, const void* data, size_t bytes) {
    const auto* p = static_cast<const uint8_t*>(data);
    const size_t a = bytes / 3, b = 2 * bytes / 3;
    ASSERT_TRUE(writer->write(id, b, p + b, bytes - b).isOk());
    ASSERT_TRUE(writer->write(id, a, p + a, b - a).isOk());
    ASSERT_TRUE(writer->write(id, 0, p, a).isOk());
  };
  backwards(SectionId::kBrickOccupancy, v.occupancy.data(), v.occupancy.size() * 4);
  backwards(SectionId::kBrickRank, v.rank.data(), v.rank.size() * 4);
  backwards(SectionId::kBrickVoxelBase, v.voxelBase.data(), v.voxelBase.size() * 4);
  backwards(SectionId::kRowStart, v.rowStarts.data(), v.rowStarts.size() * 2);
  backwards(SectionId::kRowMask, v.rowMasks.data(), v.rowMasks.size() * 4);
  ASSERT_TRUE(writer->write(SectionId::kValues, 0, v.values.data(), v.values.size()).isOk());
  ASSERT_TRUE(writer->write(SectionId::kValues, 0, v.values.data(), v.values.size()).isOk());
  // Gradients: the first half only in order, the rest never written until a gap-filling write.
  const size_t half = v.gradients.size() / 2;
  ASSERT_TRUE(writer->write(SectionId::kGradients, 0, v.gradients.data(), half * 2).isOk());
  ASSERT_TRUE(writer
                  ->write(SectionId::kGradients, half * 2, v.gradients.data() + half,
                          (v.gradients.size() - half) * 2)
                  .isOk());
  ASSERT_TRUE(writer->commit(v.metaJson).isOk());

  EXPECT_EQ(testing::readBytes(dir.file("shuffled.vxl")),
            testing::readBytes(dir.file("in_order.vxl")));
  auto file = pack::openFile(dir.file("shuffled.vxl"));
  ASSERT_TRUE(file) << file.message();
  auto report = validateFile(*file);
  EXPECT_TRUE(report) << report.message();
}

TEST(FormatRoundTrip, BuilderRejectsDuplicatesAndOutsideVoxels) {
  VolumeDescription d;
  d.dims = {4, 4, 4};
  BrickedVolumeBuilder a(d);
  a.add(1, 1, 1, 1, 0);
  a.add(1, 1, 1, 2, 0);
  EXPECT_EQ(a.build().code(), ErrorCode::kInvalidArgument);
  BrickedVolumeBuilder b(d);
  b.add(4, 0, 0, 1, 0);
  EXPECT_EQ(b.build().code(), ErrorCode::kInvalidArgument);
}

}  // namespace
}  // namespace voxlink::format
