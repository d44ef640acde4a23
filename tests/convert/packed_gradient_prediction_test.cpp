// SPDX-License-Identifier: BSD-3-Clause
// The gradient prediction packing stores GRAD against (pack/detail/gradient_predictor.h): it finds
// the converter's gradients on real CT, its eight-cell kernels agree with the per-voxel code, and
// adding it in place or a range at a time equals the whole section's.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <span>
#include <string>
#include <vector>

#include "base/parallel_for.h"
#include "convert/converter.h"
#include "format/bricked_volume.h"
#include "format/gradient_codec.h"
#include "format/scene_builder.h"
#include "format/voxel_locator.h"
#include "pack/detail/dense_brick_rows.h"
#include "pack/detail/gradient_predictor.h"
#include "pack/open_file.h"
#include "pack/packed_file.h"
#include "tests/convert/packed_fixtures.h"
#include "tests/convert/volume_fixtures.h"
#include "tests/support/test_util.h"

namespace voxlink::pack {
namespace {

using format::Axis;
using format::encodeGradient;
using format::MaterialRecord;
using format::sampleSlots;
using format::SceneBuilder;
using format::VolumeDescription;
using format::VoxelLocator;
using format::writeBrickedVolume;
using test::convertReal;
using test::kCarp;
using test::kFoot;
using test::TempDir;

TEST(PackedGradientPrediction, PredictionFindsTheConvertersGradientsForMostVoxels) {
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
TEST(PackedGradientPrediction, DenseBrickKernelsPredictThePerVoxelCodes) {
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

TEST(PackedGradientPrediction, AddingThePredictionInPlaceEqualsAddingItAfterwards) {
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
TEST(PackedGradientPrediction, RangePredictionsEqualTheWholeSections) {
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

}  // namespace
}  // namespace voxlink::pack
