// The brick tables the ray tracers read instead of the occupancy and rank sections, against
// brute force over every voxel, for every brick size and predominant axis.
#include <gtest/gtest.h>

#include <cmath>

#include "format/voxel_locator.h"
#include "tests/support/test_util.h"
#include "tests/viewer/volume_fixtures.h"
#include "viewer/core/brick_lookup.h"

namespace voxlink::viewer {
namespace {

// Scattered voxels and a thin shell, dims no multiple of any brick size, and a corner voxel so
// that the last brick of every axis is occupied somewhere.
DenseVolume scatteredShell() {
  return testing::makeVolume({37, 21, 50}, {1, 1, 1}, [](int x, int y, int z) {
    const double r = std::hypot(x - 18.0, y - 10.0, (z - 25.0) * 0.5);
    const bool shell = std::abs(r - 9.0) < 0.6;
    const bool speck = (x * 7 + y * 13 + z * 29) % 211 == 0;
    const bool corner = x == 36 && y == 20 && z == 49;
    return shell || speck || corner ? 200.0 : 0.0;
  });
}

TEST(BrickLookup, TablesMatchBruteForce) {
  const DenseVolume dense = scatteredShell();
  for (uint32_t n : {4u, 8u, 16u, 32u}) {
    for (format::Axis axis : {format::Axis::kX, format::Axis::kY, format::Axis::kZ}) {
      SCOPED_TRACE(::testing::Message() << "n=" << n << " axis=" << int(axis));
      testing::SparseOptions o;
      o.brickSize = n;
      o.axis = axis;
      auto sparse = testing::sparsify(dense, [](double v) { return v > 100; }, o);
      ASSERT_TRUE(sparse) << sparse.message();
      voxlink::testing::TempDir dir;
      auto file = testing::writeAndOpen(*sparse, dir.file("b.vxl"));
      ASSERT_TRUE(file) << file.message();
      const auto& h = file->header();
      const int64_t g[3] = {h.brickGrid[0], h.brickGrid[1], h.brickGrid[2]};

      // Occupied bricks from the voxels themselves, numbered in brick order.
      std::vector<bool> occupied(file->gridBrickCount(), false);
      format::VoxelLocator locator(*file);
      for (uint32_t z = 0; z < h.dims[2]; ++z)
        for (uint32_t y = 0; y < h.dims[1]; ++y)
          for (uint32_t x = 0; x < h.dims[0]; ++x)
            if (locator.find(x, y, z) >= 0) occupied[(uint64_t{z / n} * g[1] + y / n) * g[0] + x / n] = true;

      const std::vector<uint32_t> index = occupiedIndexByBrick(*file);
      ASSERT_EQ(index.size(), occupied.size());
      uint32_t k = 0;
      for (size_t b = 0; b < occupied.size(); ++b)
        EXPECT_EQ(index[b], occupied[b] ? k++ : kEmptyBrick) << "brick " << b;
      EXPECT_EQ(k, file->occupiedBrickCount());

      // Dual brick D reads bricks D and D + 1 per axis; bricks outside the grid are empty.
      const auto dual = dualBrickGrid(h);
      const std::vector<uint32_t> bits = dualBrickOccupancy(*file);
      const uint64_t dualCount = uint64_t{dual[0]} * dual[1] * dual[2];
      ASSERT_EQ(bits.size(), (dualCount + 31) / 32);
      auto brickOccupied = [&](int64_t x, int64_t y, int64_t z) {
        if (x < 0 || y < 0 || z < 0 || x >= g[0] || y >= g[1] || z >= g[2]) return false;
        return bool(occupied[(uint64_t(z) * g[1] + uint64_t(y)) * g[0] + uint64_t(x)]);
      };
      uint64_t set = 0;
      for (int64_t z = -1; z < g[2]; ++z)
        for (int64_t y = -1; y < g[1]; ++y)
          for (int64_t x = -1; x < g[0]; ++x) {
            bool any = false;
            for (int m = 0; m < 8; ++m) any |= brickOccupied(x + (m & 1), y + ((m >> 1) & 1), z + (m >> 2));
            const uint64_t i = (uint64_t(z + 1) * dual[1] + uint64_t(y + 1)) * dual[0] + uint64_t(x + 1);
            const bool got = (bits[i >> 5] >> (i & 31)) & 1u;
            EXPECT_EQ(got, any) << "dual brick " << x << "," << y << "," << z;
            set += got;
          }
      EXPECT_GT(set, 0u);
      // Bits past the last dual brick stay clear.
      for (uint64_t i = dualCount; i < bits.size() * 32; ++i) EXPECT_EQ((bits[i >> 5] >> (i & 31)) & 1u, 0u);
    }
  }
}

TEST(BrickLookup, EmptyFileHasNoOccupiedBrick) {
  const DenseVolume dense = testing::makeVolume({9, 9, 9}, {1, 1, 1}, [](int, int, int) { return 0.0; });
  auto sparse = testing::sparsify(dense, [](double v) { return v > 100; }, {});
  ASSERT_TRUE(sparse) << sparse.message();
  voxlink::testing::TempDir dir;
  auto file = testing::writeAndOpen(*sparse, dir.file("e.vxl"));
  ASSERT_TRUE(file) << file.message();
  for (uint32_t i : occupiedIndexByBrick(*file)) EXPECT_EQ(i, kEmptyBrick);
  for (uint32_t w : dualBrickOccupancy(*file)) EXPECT_EQ(w, 0u);
}

}  // namespace
}  // namespace voxlink::viewer
