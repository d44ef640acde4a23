// SPDX-License-Identifier: BSD-3-Clause
// Sources with inactive voxels (OpenVDB): the converter keeps a voxel only where the source says
// it is active and the classification keeps its value, on every code path (8-bit counting in
// narrow lanes, table and range keeps, floats, brick sizes, slab sizes, threads). Values and
// gradients of the kept voxels are those of the same source without the mask.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "convert/converter.h"
#include "format/validator.h"
#include "format/voxel_locator.h"
#include "pack/open_file.h"
#include "tests/convert/volume_fixtures.h"
#include "tests/support/test_util.h"

namespace voxlink::convert {
namespace {

// A blob of active voxels with holes: whole bricks inactive, single voxels inactive, and
// active voxels on the volume border.
bool blob(uint32_t x, uint32_t y, uint32_t z) {
  if ((x * 7 + y * 3 + z * 5) % 11 == 0) return false;
  const int dx = int(x) - 14, dy = int(y) - 12, dz = int(z) - 9;
  return dx * dx + dy * dy + 2 * dz * dz < 190 || x == 0;
}

template <class T>
void expectOnlyActiveKept(testing::MemorySource& values, const ConvertOptions& options) {
  testing::TempDir dir;
  auto whole = convertVolume(values, options, dir.file("whole.vxl"));
  ASSERT_TRUE(whole) << whole.message();
  testing::PartlyActiveSource masked(values, blob);
  auto summary = convertVolume(masked, options, dir.file("masked.vxl"));
  ASSERT_TRUE(summary) << summary.message();
  auto file = pack::openFile(dir.file("masked.vxl"));
  ASSERT_TRUE(file) << file.message();
  ASSERT_TRUE(format::validateFile(*file));
  auto reference = pack::openFile(dir.file("whole.vxl"));
  ASSERT_TRUE(reference) << reference.message();
  const format::VoxelLocator locator(*file), referenceLocator(*reference);
  const auto& info = values.info();
  const T* data = reinterpret_cast<const T*>(values.bytes().data());
  uint64_t expected = 0;
  for (uint32_t z = 0; z < info.dims[2]; ++z)
    for (uint32_t y = 0; y < info.dims[1]; ++y)
      for (uint32_t x = 0; x < info.dims[0]; ++x) {
        const double v =
            static_cast<double>(data[(uint64_t{z} * info.dims[1] + y) * info.dims[0] + x]);
        const bool keep = masked.active(x, y, z) && options.classification.keeps(v);
        const int64_t index = locator.find(x, y, z);
        ASSERT_EQ(index >= 0, keep) << x << "," << y << "," << z << " v=" << v;
        if (!keep) continue;
        ++expected;
        const int64_t ref = referenceLocator.find(x, y, z);
        ASSERT_GE(ref, 0);
        EXPECT_EQ(file->value(uint64_t(index)), reference->value(uint64_t(ref)));
        EXPECT_EQ(file->gradientCodes()[size_t(index)], reference->gradientCodes()[size_t(ref)]);
      }
  EXPECT_EQ(file->voxelCount(), expected);
  EXPECT_GT(expected, 0u);
  EXPECT_LT(expected, reference->voxelCount());
}

TEST(InactiveVoxels, NeverKeptWhateverTheKeepRule) {
  auto ball = testing::makeBall({29, 26, 21});
  for (uint32_t brick : {4u, 8u, 16u}) {
    SCOPED_TRACE(brick);
    ConvertOptions o;
    o.brickSize = brick;
    o.classification = keepAllClassification();  // a range keep over the whole type
    expectOnlyActiveKept<uint8_t>(*ball, o);
    o.classification = *thresholdClassification({"60"});
    expectOnlyActiveKept<uint8_t>(*ball, o);
    o.classification = *thresholdClassification({"20,40", "150,200"});  // a table keep
    expectOnlyActiveKept<uint8_t>(*ball, o);
  }
}

TEST(InactiveVoxels, FloatSourcesSlabsAndThreads) {
  auto f = testing::makeVolume<float>({29, 26, 21}, [](uint32_t x, uint32_t y, uint32_t z) {
    return std::sin(x * 0.3f) * std::cos(y * 0.2f) + 0.1f * z;
  });
  for (uint32_t slab : {1u, 7u, 64u}) {
    for (unsigned threads : {1u, 3u}) {
      SCOPED_TRACE(::testing::Message() << "slab " << slab << " threads " << threads);
      ConvertOptions o;
      o.slabSlices = slab;
      o.threads = threads;
      o.classification = keepAllClassification();
      expectOnlyActiveKept<float>(*f, o);
      o.classification = *thresholdClassification({"0.2"});
      expectOnlyActiveKept<float>(*f, o);
    }
  }
}

TEST(InactiveVoxels, SequentialSourceReadsTheMaskToo) {
  auto ball = testing::makeBall({29, 26, 21}, /*sequential=*/true);
  ConvertOptions o;
  o.slabSlices = 4;
  o.classification = keepAllClassification();
  expectOnlyActiveKept<uint8_t>(*ball, o);
}

}  // namespace
}  // namespace voxlink::convert
