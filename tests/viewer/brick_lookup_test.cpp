// The brick tables the ray tracers read instead of the occupancy and rank sections, against
// brute force over every voxel, for every brick size and predominant axis.
#include "viewer/core/brick_lookup.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>

#include "format/voxel_locator.h"
#include "tests/support/test_util.h"
#include "tests/viewer/volume_fixtures.h"
#include "viewer/core/brick_bounds.h"

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
      voxlink::testing::TempDir dir;
      auto file = testing::thresholdedFile(dense, 100, n, axis, dir.file("b.vxl"));
      ASSERT_TRUE(file) << file.message();
      const auto& h = file->header();
      const int64_t g[3] = {h.brickGrid[0], h.brickGrid[1], h.brickGrid[2]};

      // Occupied bricks from the voxels themselves, numbered in brick order.
      std::vector<bool> occupied(file->gridBrickCount(), false);
      format::VoxelLocator locator(*file);
      for (uint32_t z = 0; z < h.dims[2]; ++z)
        for (uint32_t y = 0; y < h.dims[1]; ++y)
          for (uint32_t x = 0; x < h.dims[0]; ++x)
            if (locator.find(x, y, z) >= 0)
              occupied[(uint64_t{z / n} * g[1] + y / n) * g[0] + x / n] = true;

      const std::vector<uint32_t> index = occupiedIndexByBrick(*file);
      ASSERT_EQ(index.size(), occupied.size());
      uint32_t k = 0;
      for (size_t b = 0; b < occupied.size(); ++b)
        EXPECT_EQ(index[b], occupied[b] ? k++ : kEmptyBrick) << "brick " << b;
      EXPECT_EQ(k, file->occupiedBrickCount());

      // Dual brick D reads bricks D and D + 1 per axis. Its box, by definition: the union over
      // those bricks of the cells [lo - 1, hi] their voxels' box [lo, hi] reaches, clamped to the
      // dual brick's cells [D n, D n + n - 1].
      std::vector<std::array<int64_t, 6>> voxelBox(occupied.size(),
                                                   {1 << 30, 1 << 30, 1 << 30, -1, -1, -1});
      for (uint32_t z = 0; z < h.dims[2]; ++z)
        for (uint32_t y = 0; y < h.dims[1]; ++y)
          for (uint32_t x = 0; x < h.dims[0]; ++x) {
            if (locator.find(x, y, z) < 0) continue;
            auto& box = voxelBox[(uint64_t{z / n} * g[1] + y / n) * g[0] + x / n];
            const int64_t p[3] = {x, y, z};
            for (int a = 0; a < 3; ++a) {
              box[a] = std::min(box[a], p[a]);
              box[3 + a] = std::max(box[3 + a], p[a]);
            }
          }
      const auto dual = dualBrickGrid(h);
      const std::vector<uint32_t> boxes = dualBrickBoxes(h, index, brickBounds(*file));
      ASSERT_EQ(boxes.size(), uint64_t{dual[0]} * dual[1] * dual[2]);
      uint64_t nonEmpty = 0;
      for (int64_t dz = -1; dz < g[2]; ++dz)
        for (int64_t dy = -1; dy < g[1]; ++dy)
          for (int64_t dx = -1; dx < g[0]; ++dx) {
            const int64_t D[3] = {dx, dy, dz};
            int64_t lo[3] = {n, n, n}, hi[3] = {-1, -1, -1};
            for (int m = 0; m < 8; ++m) {
              const int64_t b[3] = {dx + (m & 1), dy + ((m >> 1) & 1), dz + (m >> 2)};
              if (b[0] < 0 || b[1] < 0 || b[2] < 0 || b[0] >= g[0] || b[1] >= g[1] || b[2] >= g[2])
                continue;
              const auto& box =
                  voxelBox[(uint64_t(b[2]) * g[1] + uint64_t(b[1])) * g[0] + uint64_t(b[0])];
              if (box[3] < 0) continue;
              int64_t rlo[3], rhi[3];
              bool any = true;
              for (int a = 0; a < 3; ++a) {
                rlo[a] = std::max(box[a] - 1 - D[a] * n, int64_t{0});
                rhi[a] = std::min(box[3 + a] - D[a] * n, int64_t(n) - 1);
                any = any && rlo[a] <= rhi[a];
              }
              if (!any) continue;
              for (int a = 0; a < 3; ++a) {
                lo[a] = std::min(lo[a], rlo[a]);
                hi[a] = std::max(hi[a], rhi[a]);
              }
            }
            const uint64_t i =
                (uint64_t(dz + 1) * dual[1] + uint64_t(dy + 1)) * dual[0] + uint64_t(dx + 1);
            if (hi[0] < 0) {
              EXPECT_EQ(boxes[i], kEmptyDualBrick) << "dual brick " << dx << "," << dy << "," << dz;
              continue;
            }
            ++nonEmpty;
            ASSERT_NE(boxes[i], kEmptyDualBrick) << "dual brick " << dx << "," << dy << "," << dz;
            const BrickBox got = unpackBrickBox(boxes[i]);
            for (int a = 0; a < 3; ++a) {
              EXPECT_EQ(got.lo[a], uint32_t(lo[a]))
                  << "dual brick " << dx << "," << dy << "," << dz;
              EXPECT_EQ(got.hi[a], uint32_t(hi[a]))
                  << "dual brick " << dx << "," << dy << "," << dz;
            }
          }
      EXPECT_GT(nonEmpty, 0u);

      // What the renderer relies on: every cell with a stored corner lies in its dual brick's box.
      for (int64_t z = -1; z < int64_t(h.dims[2]); ++z)
        for (int64_t y = -1; y < int64_t(h.dims[1]); ++y)
          for (int64_t x = -1; x < int64_t(h.dims[0]); ++x) {
            bool stored = false;
            for (int m = 0; m < 8 && !stored; ++m) {
              const int64_t v[3] = {x + (m & 1), y + ((m >> 1) & 1), z + (m >> 2)};
              stored = v[0] >= 0 && v[1] >= 0 && v[2] >= 0 && locator.find(v[0], v[1], v[2]) >= 0;
            }
            if (!stored) continue;
            const int64_t c[3] = {x, y, z};
            int64_t Dc[3];
            for (int a = 0; a < 3; ++a) Dc[a] = (c[a] + n) / n - 1;  // floor(c / n), c >= -1
            const uint64_t i = (uint64_t(Dc[2] + 1) * dual[1] + uint64_t(Dc[1] + 1)) * dual[0] +
                               uint64_t(Dc[0] + 1);
            ASSERT_NE(boxes[i], kEmptyDualBrick) << "cell " << x << "," << y << "," << z;
            const BrickBox box = unpackBrickBox(boxes[i]);
            for (int a = 0; a < 3; ++a) {
              EXPECT_GE(c[a] - Dc[a] * n, int64_t(box.lo[a]))
                  << "cell " << x << "," << y << "," << z;
              EXPECT_LE(c[a] - Dc[a] * n, int64_t(box.hi[a]))
                  << "cell " << x << "," << y << "," << z;
            }
          }
    }
  }
}

TEST(BrickLookup, EmptyFileHasNoOccupiedBrick) {
  const DenseVolume dense =
      testing::makeVolume({9, 9, 9}, {1, 1, 1}, [](int, int, int) { return 0.0; });
  auto sparse = testing::sparsify(dense, [](double v) { return v > 100; }, {});
  ASSERT_TRUE(sparse) << sparse.message();
  voxlink::testing::TempDir dir;
  auto file = testing::writeAndOpen(*sparse, dir.file("e.vxl"));
  ASSERT_TRUE(file) << file.message();
  for (uint32_t i : occupiedIndexByBrick(*file)) EXPECT_EQ(i, kEmptyBrick);
  for (uint32_t w : dualBrickBoxes(file->header(), occupiedIndexByBrick(*file), brickBounds(*file)))
    EXPECT_EQ(w, kEmptyDualBrick);
}

}  // namespace
}  // namespace voxlink::viewer
