// SPDX-License-Identifier: BSD-3-Clause
// The brick tables the ray tracers read instead of the occupancy and rank sections, against
// brute force over every voxel, for every brick size and predominant axis.
#include "render/brick_lookup.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>

#include "format/bricked_volume.h"
#include "format/voxel_locator.h"
#include "pack/open_file.h"
#include "render/brick_bounds.h"
#include "tests/support/test_util.h"
#include "tests/viewer/volume_fixtures.h"

namespace voxlink::render {

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

      // The index covers the smallest box of bricks holding every occupied one.
      const BrickRange range = occupiedBrickRange(*file);
      std::array<int64_t, 3> first{g[0], g[1], g[2]}, last{-1, -1, -1};
      for (int64_t bz = 0, b = 0; bz < g[2]; ++bz)
        for (int64_t by = 0; by < g[1]; ++by)
          for (int64_t bx = 0; bx < g[0]; ++bx, ++b) {
            if (!occupied[b]) continue;
            const int64_t c[3] = {bx, by, bz};
            for (int a = 0; a < 3; ++a) {
              first[a] = std::min(first[a], c[a]);
              last[a] = std::max(last[a], c[a]);
            }
          }
      for (int a = 0; a < 3; ++a) {
        EXPECT_EQ(range.lo[a], uint32_t(first[a])) << "axis " << a;
        EXPECT_EQ(range.size[a], uint32_t(last[a] - first[a] + 1)) << "axis " << a;
      }
      const std::vector<uint32_t> index = occupiedIndexByBrick(*file, range);
      ASSERT_EQ(index.size(), range.count());
      uint32_t k = 0;
      for (int64_t bz = 0, b = 0; bz < g[2]; ++bz)
        for (int64_t by = 0; by < g[1]; ++by)
          for (int64_t bx = 0; bx < g[0]; ++bx, ++b) {
            const bool inside = bx >= first[0] && bx <= last[0] && by >= first[1] &&
                                by <= last[1] && bz >= first[2] && bz <= last[2];
            if (!inside) {
              EXPECT_FALSE(occupied[b]) << "brick " << b << " outside the range";
              continue;
            }
            EXPECT_EQ(index[range.local(bx, by, bz)], occupied[b] ? k++ : kEmptyBrick)
                << "brick " << b;
          }
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
      const BrickRange dualRange = dualBrickRange(range);
      const std::vector<uint32_t> table = dualBrickBoxes(*file, range, brickBounds(*file));
      ASSERT_EQ(table.size(), dualRange.count());
      // The table over the whole dual grid: what a lookup outside the range gives is empty.
      std::vector<uint32_t> boxes(uint64_t{dual[0]} * dual[1] * dual[2], kEmptyDualBrick);
      for (uint64_t z = 0; z < dual[2]; ++z)
        for (uint64_t y = 0; y < dual[1]; ++y)
          for (uint64_t x = 0; x < dual[0]; ++x) {
            const bool inside = x >= dualRange.lo[0] && x < dualRange.lo[0] + dualRange.size[0] &&
                                y >= dualRange.lo[1] && y < dualRange.lo[1] + dualRange.size[1] &&
                                z >= dualRange.lo[2] && z < dualRange.lo[2] + dualRange.size[2];
            if (inside) boxes[(z * dual[1] + y) * dual[0] + x] = table[dualRange.local(x, y, z)];
          }
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

      // The 8 bricks' occupied indices per dual brick, 16 bits each, brick D + (m & 1, m >> 1
      // & 1, m >> 2) at bits 16 m, against the occupied bricks counted in file order.
      ASSERT_TRUE(dualBrickIndicesFit(file->occupiedBrickCount()));
      const std::vector<uint32_t> indices = dualBrickIndices(range, index);
      ASSERT_EQ(indices.size(), 4 * dualRange.count());
      std::vector<uint32_t> kOf(occupied.size(), kEmptyBrick16);
      for (uint32_t b = 0, next = 0; b < occupied.size(); ++b)
        if (occupied[b]) kOf[b] = next++;
      for (uint64_t z = 0; z < dualRange.size[2]; ++z)
        for (uint64_t y = 0; y < dualRange.size[1]; ++y)
          for (uint64_t x = 0; x < dualRange.size[0]; ++x) {
            const int64_t c[3] = {int64_t(dualRange.lo[0] + x), int64_t(dualRange.lo[1] + y),
                                  int64_t(dualRange.lo[2] + z)};
            const uint32_t* words =
                &indices[4 * dualRange.local(uint64_t(c[0]), uint64_t(c[1]), uint64_t(c[2]))];
            for (int m = 0; m < 8; ++m) {
              const int64_t b[3] = {c[0] - 1 + (m & 1), c[1] - 1 + ((m >> 1) & 1),
                                    c[2] - 1 + (m >> 2)};
              const bool inGrid =
                  b[0] >= 0 && b[1] >= 0 && b[2] >= 0 && b[0] < g[0] && b[1] < g[1] && b[2] < g[2];
              const uint32_t want =
                  inGrid ? kOf[(uint64_t(b[2]) * g[1] + uint64_t(b[1])) * g[0] + uint64_t(b[0])]
                         : kEmptyBrick16;
              EXPECT_EQ((words[m >> 1] >> (16 * (m & 1))) & 0xFFFFu, want)
                  << "dual cell " << c[0] << "," << c[1] << "," << c[2] << " brick " << m;
            }
          }

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
  const BrickRange range = occupiedBrickRange(*file);
  EXPECT_EQ(range.count(), 0u);
  EXPECT_EQ(dualBrickRange(range).count(), 0u);
  EXPECT_TRUE(occupiedIndexByBrick(*file, range).empty());
  EXPECT_TRUE(dualBrickBoxes(*file, range, brickBounds(*file)).empty());
}

// The file: one voxel in a 65536 x 32768 x 1 grid of 4-voxel bricks (134 million
// bricks). The tables cover the one occupied brick and the 8 dual cells around it; covering
// the grid, they took 14 GB.
TEST(BrickLookup, TablesFollowTheOccupiedBricksNotTheGrid) {
  format::VolumeDescription d;
  d.dims = {65536, 32768, 1};
  d.brickSize = 4;
  d.valueType = StoredType::kU8;
  d.sourceType = ScalarType::kU8;
  format::BrickedVolumeBuilder builder(d);
  builder.add(40001, 20002, 0, 7, 0);
  auto volume = builder.build();
  ASSERT_TRUE(volume) << volume.message();
  voxlink::testing::TempDir dir;
  ASSERT_TRUE(format::writeBrickedVolume(dir.file("one.vxl"), *volume).isOk());
  auto file = pack::openFile(dir.file("one.vxl"));
  ASSERT_TRUE(file) << file.message();
  const BrickRange range = occupiedBrickRange(*file);
  EXPECT_EQ(range.lo, (std::array<uint32_t, 3>{10000, 5000, 0}));
  EXPECT_EQ(range.size, (std::array<uint32_t, 3>{1, 1, 1}));
  EXPECT_EQ(occupiedIndexByBrick(*file, range), std::vector<uint32_t>{0});
  const std::vector<uint32_t> boxes = dualBrickBoxes(*file, range, brickBounds(*file));
  ASSERT_EQ(boxes.size(), 8u);
  // Voxel (40001, 20002, 0) is cell (1, 2, 0) of its brick; a sample blends it from cells
  // (0..1, 1..2, -1..0): in dual brick (10000, 5000, 0) (dual cell + 1) those are x 0-1, y 1-2,
  // z 0; the dual bricks before it along x and y reach nothing, the one before along z reaches
  // its last cell (z = -1 = 3 of dual brick -1).
  auto cells = [](uint32_t word) {
    const BrickBox b = unpackBrickBox(word);
    return std::array<uint32_t, 6>{b.lo[0], b.lo[1], b.lo[2], b.hi[0], b.hi[1], b.hi[2]};
  };
  const BrickRange dual = dualBrickRange(range);
  EXPECT_EQ(cells(boxes[dual.local(10001, 5001, 1)]), (std::array<uint32_t, 6>{0, 1, 0, 1, 2, 0}));
  EXPECT_EQ(cells(boxes[dual.local(10001, 5001, 0)]), (std::array<uint32_t, 6>{0, 1, 3, 1, 2, 3}));
  EXPECT_EQ(boxes[dual.local(10000, 5001, 1)], kEmptyDualBrick);
}

}  // namespace
}  // namespace voxlink::render
