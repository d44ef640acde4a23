// SPDX-License-Identifier: BSD-3-Clause
// The per-brick boxes of stored voxels the ray tracer clips to, against brute force over every
// cell, for every predominant axis and brick size.
#include "render/brick_bounds.h"

#include <gtest/gtest.h>

#include <cmath>

#include "format/voxel_locator.h"
#include "tests/support/test_util.h"
#include "tests/viewer/volume_fixtures.h"

namespace voxlink::render {

namespace {

TEST(BrickBounds, PackingRoundTrips) {
  const BrickBox box{{0, 7, 31}, {31, 9, 31}};
  const BrickBox back = unpackBrickBox(packBrickBox(box));
  for (int a = 0; a < 3; ++a) {
    EXPECT_EQ(back.lo[a], box.lo[a]);
    EXPECT_EQ(back.hi[a], box.hi[a]);
  }
}

TEST(BrickBounds, EachBoxIsTheTightBoxOfItsBricksVoxels) {
  // Scattered voxels and a thin shell in a volume that is no multiple of any brick size.
  const DenseVolume dense = testing::makeVolume({37, 21, 50}, {1, 1, 1}, [](int x, int y, int z) {
    const double r = std::hypot(x - 18.0, y - 10.0, (z - 25.0) * 0.5);
    const bool shell = std::abs(r - 9.0) < 0.6;
    const bool speck = (x * 7 + y * 13 + z * 29) % 97 == 0;
    return shell || speck ? 200.0 : 0.0;
  });
  for (uint32_t n : {4u, 8u, 16u, 32u}) {
    for (format::Axis axis : {format::Axis::kX, format::Axis::kY, format::Axis::kZ}) {
      voxlink::testing::TempDir dir;
      auto file = testing::thresholdedFile(dense, 100, n, axis, dir.file("b.vxl"));
      ASSERT_TRUE(file) << file.message();
      const std::vector<uint32_t> words = brickBounds(*file);
      ASSERT_EQ(words.size(), file->occupiedBrickCount());

      // Brute force: the box of every brick's stored voxels, in occupied-brick order.
      const auto& h = file->header();
      std::vector<BrickBox> expected;
      std::vector<int64_t> brickToK(uint64_t{h.brickGrid[0]} * h.brickGrid[1] * h.brickGrid[2], -1);
      format::VoxelLocator locator(*file);
      for (uint32_t z = 0; z < h.dims[2]; ++z)
        for (uint32_t y = 0; y < h.dims[1]; ++y)
          for (uint32_t x = 0; x < h.dims[0]; ++x) {
            if (locator.find(x, y, z) < 0) continue;
            brickToK[(uint64_t{z / n} * h.brickGrid[1] + y / n) * h.brickGrid[0] + x / n] =
                0;  // seen
          }
      // Number occupied bricks in brick order, then grow their boxes.
      int64_t k = 0;
      for (auto& v : brickToK)
        if (v != -1) v = k++;
      ASSERT_EQ(uint64_t(k), file->occupiedBrickCount());
      expected.assign(k, BrickBox{{n, n, n}, {0, 0, 0}});
      for (uint32_t z = 0; z < h.dims[2]; ++z)
        for (uint32_t y = 0; y < h.dims[1]; ++y)
          for (uint32_t x = 0; x < h.dims[0]; ++x) {
            if (locator.find(x, y, z) < 0) continue;
            const uint32_t p[3] = {x, y, z};
            const uint64_t b = (uint64_t{z / n} * h.brickGrid[1] + y / n) * h.brickGrid[0] + x / n;
            BrickBox& box = expected[brickToK[b]];
            for (int a = 0; a < 3; ++a) {
              box.lo[a] = std::min(box.lo[a], p[a] % n);
              box.hi[a] = std::max(box.hi[a], p[a] % n);
            }
          }
      for (int64_t i = 0; i < k; ++i) {
        const BrickBox got = unpackBrickBox(words[i]);
        for (int a = 0; a < 3; ++a) {
          EXPECT_EQ(got.lo[a], expected[i].lo[a])
              << "n=" << n << " axis=" << int(axis) << " brick " << i;
          EXPECT_EQ(got.hi[a], expected[i].hi[a])
              << "n=" << n << " axis=" << int(axis) << " brick " << i;
        }
      }
    }
  }
}

}  // namespace
}  // namespace voxlink::render
