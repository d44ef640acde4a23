// SPDX-License-Identifier: BSD-3-Clause
// Packed files (pack/packed_file.h) on converted real CT: they unpack to the original bytes,
// are much smaller, and every kind of damage is refused with a message naming the section.
#include "pack/packed_file.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>

#include "base/crc32c.h"
#include "base/parallel_for.h"
#include "convert/converter.h"
#include "format/bricked_volume.h"
#include "format/derived_sections.h"
#include "format/gradient_codec.h"
#include "format/scene_builder.h"
#include "format/validator.h"
#include "format/voxel_locator.h"
#include "pack/detail/dense_brick_rows.h"
#include "pack/detail/gradient_predictor.h"
#include "pack/open_file.h"
#include "sources/volume_source.h"
#include "tests/convert/volume_fixtures.h"
#include "tests/support/test_util.h"

namespace voxlink::format {

using pack::addPredictedGradientCodes;
using pack::denseBrickRowsAvailable;
using pack::GradientPrediction;
using pack::GradientRangePredictor;
using pack::kPackChunkBytes;
using pack::packFile;
using pack::PackOptions;
using pack::predictGradientCodes;
using pack::predictGradientCodesPerVoxel;
using pack::unpackFile;

namespace {

using ::voxlink::testing::TempDir;

constexpr const char* kFoot = "ct/openscivis_lossy/foot_256x256x256_uint8_lossy.nrrd";
constexpr const char* kCarp = "ct/openscivis_lossy/carp_128x128x256_uint16_lossy.nrrd";

std::string convertReal(const TempDir& dir, const std::string& relative, const char* threshold,
                        const char* valueType = nullptr, uint32_t brickSize = 8,
                        Axis axis = Axis::kZ) {
  auto source = sources::openVolume(testing::dataPath(relative), {});
  EXPECT_TRUE(source) << source.message();
  convert::ConvertOptions options;
  options.brickSize = brickSize;
  options.axis = axis;
  options.classification = convert::thresholdClassification({threshold}).value();
  if (valueType) {
    options.storedType = parseStoredName(valueType);
    options.errorBound = 1e9;  // f16 rounds the larger values: allowed, the file stays valid
  }
  const std::string path = dir.file("in.vxl");
  auto converted = convert::convertVolume(**source, options, path);
  EXPECT_TRUE(converted) << converted.message();
  return path;
}

struct Packed {
  std::vector<uint8_t> original, packed;
};

Packed packReal(const TempDir& dir, const std::string& path, bool predict = true) {
  Packed out;
  auto file = pack::openValidatedFile(path);
  EXPECT_TRUE(file) << file.message();
  PackOptions options;
  options.predictGradients = predict;
  auto report = packFile(*file, dir.file("packed.vxl"), options);
  EXPECT_TRUE(report) << report.message();
  out.original = testing::readBytes(path);
  out.packed = testing::readBytes(dir.file("packed.vxl"));
  return out;
}

std::vector<uint8_t> unpacked(const std::vector<uint8_t>& packed) {
  auto file = unpackFile(packed, "p.vxl", uint64_t{1} << 32);
  EXPECT_TRUE(file) << file.message();
  if (!file) return {};
  return {file->bytes().begin(), file->bytes().end()};
}

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

TEST(PackedFile, PredictionFindsTheConvertersGradientsForMostVoxels) {
  VOXLINK_REQUIRE_DATA(kFoot);
  TempDir dir;
  auto file = pack::openValidatedFile(convertReal(dir, kFoot, "60"));
  ASSERT_TRUE(file);
  const auto stored = file->gradientCodes();
  const VoxelLocator locator(*file);
  const auto dims = file->header().dims;
  for (GradientPrediction kind : {GradientPrediction::kExact, GradientPrediction::kPortable}) {
    SCOPED_TRACE(kind == GradientPrediction::kExact ? "exact" : "portable");
    std::vector<uint16_t> predicted(file->voxelCount());
    predictGradientCodes(*file, predicted, kind);
    // Where all six neighbours are stored, the stored values give the converter's differences.
    uint64_t interior = 0, same = 0;
    locator.forEachVoxel([&](uint32_t x, uint32_t y, uint32_t z, uint64_t i) {
      if (x == 0 || y == 0 || z == 0 || x + 1 == dims[0] || y + 1 == dims[1] || z + 1 == dims[2])
        return;
      if (locator.find(x - 1, y, z) < 0 || locator.find(x + 1, y, z) < 0 ||
          locator.find(x, y - 1, z) < 0 || locator.find(x, y + 1, z) < 0 ||
          locator.find(x, y, z - 1) < 0 || locator.find(x, y, z + 1) < 0)
        return;
      ++interior;
      same += predicted[i] == stored[i];
    });
    EXPECT_GT(interior, file->voxelCount() / 3);
    EXPECT_GT(double(same) / double(interior), 0.99) << same << " of " << interior;
    // Threads do not change it.
    std::vector<uint16_t> single(predicted.size());
    predictGradientCodes(*file, single, kind, 1);
    EXPECT_EQ(single, predicted);
  }
}

// The eight-cell kernels (pack/detail/dense_brick_rows.h) must predict the per-voxel codes bit for
// bit, or a file packed on a CPU that has them would not unpack on one that has not: every
// brick size they take, every depth axis, 8- and 16-bit, half and float values.
TEST(PackedFile, DenseBrickKernelsPredictThePerVoxelCodes) {
  VOXLINK_REQUIRE_DATA(kFoot);
  VOXLINK_REQUIRE_DATA(kCarp);
  if (!denseBrickRowsAvailable()) GTEST_SKIP() << "no AVX2 here: the kernels are not used";
  TempDir dir;
  struct Case {
    const char* data;
    const char* threshold;
    const char* valueType;
    uint32_t brickSize;
    Axis axis;
  };
  for (const Case& c :
       {Case{kFoot, "60", nullptr, 8, Axis::kZ}, Case{kFoot, "60", nullptr, 8, Axis::kX},
        Case{kFoot, "60", nullptr, 16, Axis::kY}, Case{kFoot, "60", nullptr, 32, Axis::kZ},
        Case{kCarp, "1250", nullptr, 8, Axis::kY}, Case{kCarp, "1250", "f16", 16, Axis::kX},
        Case{kCarp, "1250", "f32", 8, Axis::kZ}}) {
    SCOPED_TRACE(std::string(c.data) + " " + (c.valueType ? c.valueType : "") + " brick " +
                 std::to_string(c.brickSize) + " axis " + std::to_string(int(c.axis)));
    auto file = pack::openValidatedFile(
        convertReal(dir, c.data, c.threshold, c.valueType, c.brickSize, c.axis));
    ASSERT_TRUE(file) << file.message();
    std::vector<uint16_t> perVoxel(file->voxelCount());
    predictGradientCodesPerVoxel(*file, perVoxel, GradientPrediction::kPortable);
    for (unsigned threads : {1u, 2u}) {
      std::vector<uint16_t> dense(file->voxelCount());
      predictGradientCodes(*file, dense, GradientPrediction::kPortable, threads);
      uint64_t differ = 0;
      for (uint64_t i = 0; i < dense.size(); ++i) differ += dense[i] != perVoxel[i];
      EXPECT_EQ(differ, 0u) << "of " << dense.size() << " with " << threads << " threads";
    }
  }
}

// Unpacking adds the prediction to GRAD's residuals in place (addPredictedGradientCodes): every
// entry exactly once, whatever the number of threads, with both predictions, for a volume (bricks
// at and away from its faces, more than one batch of bricks) and a scene (codes by VMSK slot,
// voxels that hold only a surface in between). No real data needed.
// A ball as a volume file and as a scene (two voxels of three hold a volume sample, the third a
// surface), both of more than one batch of bricks: the paths of the two predictions.
std::vector<std::string> ballVolumeAndScene(const TempDir& dir) {
  const std::array<uint32_t, 3> dims = {96, 80, 72};
  auto ball = testing::makeBall(dims);
  convert::ConvertOptions options;
  options.classification = convert::thresholdClassification({"40"}).value();
  const std::string volume = dir.file("ball.vxl");
  EXPECT_TRUE(convert::convertVolume(*ball, options, volume));
  VolumeDescription description;
  description.dims = dims;
  description.valueMin = 40;
  description.valueMax = 255;
  SceneBuilder builder(description);
  MaterialRecord grey{};
  grey.color[0] = grey.color[1] = grey.color[2] = 0.5f;
  grey.opacity = grey.refractiveIndex = 1;
  builder.setMaterials({grey});
  const uint8_t* values = ball->bytes().data();
  for (uint32_t z = 0; z < dims[2]; ++z)
    for (uint32_t y = 0; y < dims[1]; ++y)
      for (uint32_t x = 0; x < dims[0]; ++x) {
        const uint8_t v = *values++;
        if (v < 40) continue;
        if ((x + y + z) % 3 != 0)
          builder.addVolumeSample(x, y, z, v, encodeGradient(1.0, 0.0, 0.0));
        else
          builder.addSurface(x, y, z, encodeGradient(0.0, 1.0, 0.0), 0);
      }
  auto built = builder.build();
  EXPECT_TRUE(built) << built.message();
  const std::string scene = dir.file("scene.vxl");
  EXPECT_TRUE(built && writeBrickedVolume(scene, *built).isOk());
  return {volume, scene};
}

TEST(PackedFile, AddingThePredictionInPlaceEqualsAddingItAfterwards) {
  TempDir dir;
  for (const std::string& path : ballVolumeAndScene(dir)) {
    auto file = pack::openValidatedFile(path);
    ASSERT_TRUE(file) << file.message();
    ASSERT_GT(file->occupiedBrickCount(), 256u);  // more than one batch of bricks
    const uint64_t slots = sampleSlots(file->header());
    std::vector<uint16_t> residual(slots);
    uint32_t state = 12345;
    for (uint16_t& r : residual)
      r = static_cast<uint16_t>((state = state * 1664525u + 1013904223u) >> 16);
    for (GradientPrediction kind : {GradientPrediction::kExact, GradientPrediction::kPortable}) {
      std::vector<uint16_t> expected(slots);
      predictGradientCodes(*file, expected, kind, 1);
      for (uint64_t i = 0; i < slots; ++i)
        expected[i] = static_cast<uint16_t>(expected[i] + residual[i]);
      for (unsigned threads : {1u, 2u, 3u}) {
        SCOPED_TRACE(path + (kind == GradientPrediction::kExact ? " exact, " : " portable, ") +
                     std::to_string(threads) + " threads");
        std::vector<uint16_t> added = residual;
        addPredictedGradientCodes(*file, added, kind, threads);
        EXPECT_EQ(added, expected);
      }
    }
  }
}

// Packing predicts GRAD a chunk at a time: any range, from several threads at once, must give
// the codes of the whole section's prediction (ranges that start or end inside a brick, cover
// many bricks, or reach past the last entry, which gives 0).
TEST(PackedFile, RangePredictionsEqualTheWholeSections) {
  TempDir dir;
  for (const std::string& path : ballVolumeAndScene(dir)) {
    auto file = pack::openValidatedFile(path);
    ASSERT_TRUE(file) << file.message();
    const uint64_t slots = sampleSlots(file->header());
    for (GradientPrediction kind : {GradientPrediction::kExact, GradientPrediction::kPortable}) {
      std::vector<uint16_t> expected(slots);
      predictGradientCodes(*file, expected, kind, 1);
      const GradientRangePredictor predictor(*file, kind);
      for (uint64_t size : {uint64_t{1}, uint64_t{7}, uint64_t{1000}, uint64_t{65536}, slots}) {
        SCOPED_TRACE(path + (kind == GradientPrediction::kExact ? " exact" : " portable") +
                     ", ranges of " + std::to_string(size));
        const uint64_t ranges = (slots + size - 1) / size + 1;  // the last one past the end
        std::vector<uint16_t> got(ranges * size, 1);
        parallelFor(ranges, 2, [&](uint64_t r) {
          predictor.predict(r * size, std::span(got).subspan(r * size, size));
        });
        EXPECT_TRUE(std::equal(expected.begin(), expected.end(), got.begin()));
        EXPECT_TRUE(std::all_of(got.begin() + slots, got.end(), [](uint16_t c) { return c == 0; }));
      }
    }
  }
}

// Rewrites the packed table's CRC of the section whose payload holds byte `at`, so damage
// reaches the decoder instead of being caught by the checksum.
void refreshCrc(std::vector<uint8_t>& packed, uint64_t at) {
  FileHeader h;
  std::memcpy(&h, packed.data(), sizeof h);
  for (uint32_t i = 0; i < h.sectionCount; ++i) {
    SectionEntry e;
    uint8_t* slot = packed.data() + h.sectionTableOffset + i * sizeof e;
    std::memcpy(&e, slot, sizeof e);
    if (at >= e.offset && at < e.offset + e.bytes) {
      e.crc = crc32c(packed.data() + e.offset, e.bytes);
      std::memcpy(slot, &e, sizeof e);
    }
  }
}

SectionEntry packedEntry(const std::vector<uint8_t>& packed, SectionId id) {
  FileHeader h;
  std::memcpy(&h, packed.data(), sizeof h);
  for (uint32_t i = 0; i < h.sectionCount; ++i) {
    SectionEntry e;
    std::memcpy(&e, packed.data() + h.sectionTableOffset + i * sizeof e, sizeof e);
    if (e.id == static_cast<uint32_t>(id)) return e;
  }
  ADD_FAILURE() << "no section " << sectionName(id);
  return {};
}

std::string unpackError(const std::vector<uint8_t>& packed, uint64_t maxBytes = uint64_t{1} << 32) {
  auto file = unpackFile(packed, "p.vxl", maxBytes);
  if (file) return "";
  EXPECT_EQ(file.message().find('\n'), std::string::npos) << file.message();
  return file.message();
}

TEST(PackedFile, DamageIsRefusedNamingTheSection) {
  VOXLINK_REQUIRE_DATA(kFoot);
  TempDir dir;
  const Packed p = packReal(dir, convertReal(dir, kFoot, "60"));
  for (SectionId id : {SectionId::kBrickOccupancy, SectionId::kRowMask, SectionId::kValues,
                       SectionId::kGradients, SectionId::kMeta, SectionId::kPack}) {
    SCOPED_TRACE(std::string(sectionName(id)));
    const SectionEntry e = packedEntry(p.packed, id);
    // A flipped byte: the packed payload's checksum.
    std::vector<uint8_t> damaged = p.packed;
    damaged[e.offset + e.bytes / 2] ^= 0x40;
    const std::string crc = unpackError(damaged);
    EXPECT_NE(crc.find(std::string("section ") + std::string(sectionName(id))), std::string::npos)
        << crc;
    EXPECT_NE(crc.find("checksum"), std::string::npos) << crc;
    // The same damage with the checksum made to match: the decoder or the original
    // checksums catch it.
    refreshCrc(damaged, e.offset + e.bytes / 2);
    const std::string deep = unpackError(damaged);
    EXPECT_FALSE(deep.empty()) << "damage in " << sectionName(id) << " was accepted";
  }
  // Truncation anywhere.
  for (uint64_t size :
       {uint64_t{0}, uint64_t{100}, uint64_t{256}, p.packed.size() / 2, p.packed.size() - 1}) {
    std::vector<uint8_t> cut(p.packed.begin(), p.packed.begin() + long(size));
    EXPECT_FALSE(unpackError(cut).empty()) << size;
  }
  // A file that would unpack to more than the caller allows is refused before allocating.
  EXPECT_NE(unpackError(p.packed, 1 << 20).find("PACK.originalFileBytes"), std::string::npos);
  // A section whose original bytes would be decoded over the restored section table: the file
  // would then be read through a table the packed file chose.
  {
    std::vector<uint8_t> damaged = p.packed;
    const SectionEntry pack = packedEntry(damaged, SectionId::kPack);
    uint64_t tableOffset;
    uint32_t entryCount;
    std::memcpy(&entryCount, damaged.data() + pack.offset + 4, 4);
    std::memcpy(&tableOffset, damaged.data() + pack.offset + 16, 8);
    for (uint32_t i = 0; i < entryCount; ++i) {
      uint8_t* original = damaged.data() + pack.offset + 32 + 40 * i;
      uint32_t id;
      std::memcpy(&id, original, 4);
      if (id != static_cast<uint32_t>(SectionId::kBrickOccupancy)) continue;
      const uint64_t offset = tableOffset - 64, bytes = 128;
      std::memcpy(original + 8, &offset, 8);
      std::memcpy(original + 16, &bytes, 8);
    }
    refreshCrc(damaged, pack.offset);
    const std::string overlap = unpackError(damaged);
    EXPECT_NE(overlap.find("section BOCC: original bytes"), std::string::npos) << overlap;
    EXPECT_NE(overlap.find("overlap the section table"), std::string::npos) << overlap;
  }
  // An original file larger than what its table describes, with every checksum made to match:
  // the unpacked file would end in a megabyte of zeros that nothing covers.
  {
    std::vector<uint8_t> damaged = p.packed;
    const SectionEntry pack = packedEntry(damaged, SectionId::kPack);
    uint64_t fileBytes;
    std::memcpy(&fileBytes, damaged.data() + pack.offset + 8, 8);
    fileBytes += 1 << 20;
    std::memcpy(damaged.data() + pack.offset + 8, &fileBytes, 8);
    refreshCrc(damaged, pack.offset);
    const std::string inflated = unpackError(damaged);
    EXPECT_NE(inflated.find("p.vxl: the last 1048"), std::string::npos) << inflated;
    EXPECT_NE(inflated.find("belong to no section"), std::string::npos) << inflated;
  }
  // An original file too small for its header, or a table inside the header, with every checksum
  // made to match (a PACK of one entry, the restored header's checksum recomputed): restoring the
  // header would write past the file, the table over the header.
  struct Forged {
    uint64_t fileBytes, tableOffset;
    const char* message;
  };
  for (const Forged& f :
       {Forged{32, 0, "PACK.originalFileBytes: 32 bytes cannot hold the 256-byte header"},
        Forged{255, 0, "PACK.originalFileBytes: 255 bytes cannot hold the 256-byte header"},
        Forged{4096, 0, "PACK.originalTableOffset: 0 lies inside the 256-byte header"},
        Forged{4096, 100, "PACK.originalTableOffset: 100 lies inside the 256-byte header"}}) {
    SCOPED_TRACE(f.message);
    const uint64_t fileBytes = f.fileBytes;
    std::vector<uint8_t> damaged = p.packed;
    FileHeader h;
    std::memcpy(&h, damaged.data(), sizeof h);
    SectionEntry pack;
    uint8_t* packSlot = nullptr;
    for (uint32_t i = 0; i < h.sectionCount; ++i) {
      uint8_t* slot = damaged.data() + h.sectionTableOffset + i * sizeof pack;
      std::memcpy(&pack, slot, sizeof pack);
      if (pack.id == static_cast<uint32_t>(SectionId::kPack)) {
        packSlot = slot;
        break;
      }
    }
    ASSERT_NE(packSlot, nullptr);
    uint8_t* preamble = damaged.data() + pack.offset;
    const uint32_t entryCount = 1;
    const uint64_t tableOffset = f.tableOffset;
    std::memcpy(preamble + 4, &entryCount, 4);
    std::memcpy(preamble + 8, &fileBytes, 8);
    std::memcpy(preamble + 16, &tableOffset, 8);
    FileHeader original = h;
    std::memcpy(original.magic, kMagic, sizeof original.magic);
    original.sectionTableOffset = tableOffset;
    original.sectionCount = entryCount;
    const uint32_t originalCrc = headerChecksum(original);
    std::memcpy(preamble + 24, &originalCrc, 4);
    pack.bytes = 32 + 40;
    pack.crc = crc32c(preamble, pack.bytes);
    std::memcpy(packSlot, &pack, sizeof pack);
    const std::string refused = unpackError(damaged);
    EXPECT_NE(refused.find(f.message), std::string::npos) << refused;
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
}  // namespace voxlink::format
