// SPDX-License-Identifier: BSD-3-Clause
#include "render/brick_lookup.h"

#include <algorithm>

#include "format/occupied_bricks.h"
#include "render/brick_bounds.h"

namespace voxlink::render {
namespace {

// Brick coordinates of source-order brick id b.
std::array<uint32_t, 3> brickCell(const format::FileHeader& h, uint64_t b) {
  const uint64_t gx = h.brickGrid[0], gxy = gx * h.brickGrid[1];
  return {uint32_t(b % gx), uint32_t(b / gx % h.brickGrid[1]), uint32_t(b / gxy)};
}

}  // namespace

std::vector<uint32_t> occupiedBrickCells(const format::VoxLinkFile& file) {
  std::vector<uint32_t> cells;
  cells.reserve(3 * file.occupiedBrickCount());
  format::forEachOccupiedBrick(file.occupancyWords(), file.gridBrickCount(),
                               [&](uint64_t b, uint64_t) {
                                 const auto c = brickCell(file.header(), b);
                                 cells.insert(cells.end(), c.begin(), c.end());
                               });
  return cells;
}

BrickRange occupiedBrickRange(const format::VoxLinkFile& file) {
  const format::FileHeader& h = file.header();
  std::array<uint32_t, 3> lo{UINT32_MAX, UINT32_MAX, UINT32_MAX}, hi{0, 0, 0};
  bool any = false;
  format::forEachOccupiedBrick(file.occupancyWords(), file.gridBrickCount(),
                               [&](uint64_t b, uint64_t) {
                                 const auto c = brickCell(h, b);
                                 for (int a = 0; a < 3; ++a) {
                                   lo[a] = std::min(lo[a], c[a]);
                                   hi[a] = std::max(hi[a], c[a]);
                                 }
                                 any = true;
                               });
  BrickRange range;
  if (!any) return range;
  for (int a = 0; a < 3; ++a) {
    range.lo[a] = lo[a];
    range.size[a] = hi[a] - lo[a] + 1;
  }
  return range;
}

std::vector<uint32_t> occupiedIndexByBrick(const format::VoxLinkFile& file,
                                           const BrickRange& range) {
  const format::FileHeader& h = file.header();
  std::vector<uint32_t> out(range.count(), kEmptyBrick);
  format::forEachOccupiedBrick(file.occupancyWords(), file.gridBrickCount(),
                               [&](uint64_t b, uint64_t k) {
                                 const auto c = brickCell(h, b);
                                 out[range.local(c[0], c[1], c[2])] = uint32_t(k);
                               });
  return out;
}

std::array<uint32_t, 3> dualBrickGrid(const format::FileHeader& h) {
  return {h.brickGrid[0] + 1, h.brickGrid[1] + 1, h.brickGrid[2] + 1};
}

BrickRange dualBrickRange(const BrickRange& occupied) {
  BrickRange dual = occupied;
  if (occupied.count() > 0)
    for (uint32_t& s : dual.size) ++s;
  return dual;
}

std::vector<uint32_t> dualBrickBoxes(const format::VoxLinkFile& file, const BrickRange& occupied,
                                     std::span<const uint32_t> brickBoxes) {
  const format::FileHeader& h = file.header();
  const int64_t n = h.brickSize;
  const BrickRange dual = dualBrickRange(occupied);
  // Merged in place, packed: 4 bytes per dual cell (unpacked boxes of int64 took 48).
  std::vector<uint32_t> out(dual.count(), kEmptyDualBrick);
  // An occupied brick b is read by the dual bricks b - 1 and b per axis (dual cells b, b + 1).
  format::forEachOccupiedBrick(
      file.occupancyWords(), file.gridBrickCount(), [&](uint64_t b, uint64_t k) {
        const auto brick = brickCell(h, b);
        const BrickBox box = unpackBrickBox(brickBoxes[k]);
        for (uint32_t m = 0; m < 8; ++m) {
          const uint64_t c[3] = {brick[0] + (m & 1u), brick[1] + ((m >> 1) & 1u),
                                 brick[2] + (m >> 2)};  // dual cell
          // Cells reached, global: [b n + lo - 1, b n + hi]; the dual brick's: [(c - 1) n, c n -
          // 1].
          BrickBox reached;
          bool any = true;
          for (int a = 0; a < 3; ++a) {
            const int64_t origin = (int64_t(c[a]) - 1) * n;
            const int64_t lo = std::max(int64_t(brick[a]) * n + box.lo[a] - 1 - origin, int64_t{0});
            const int64_t hi = std::min(int64_t(brick[a]) * n + box.hi[a] - origin, n - 1);
            any = any && lo <= hi;
            reached.lo[a] = uint32_t(std::max<int64_t>(lo, 0));
            reached.hi[a] = uint32_t(std::max<int64_t>(hi, 0));
          }
          if (!any) continue;
          uint32_t& word = out[dual.local(c[0], c[1], c[2])];
          if (word != kEmptyDualBrick) {
            const BrickBox had = unpackBrickBox(word);
            for (int a = 0; a < 3; ++a) {
              reached.lo[a] = std::min(reached.lo[a], had.lo[a]);
              reached.hi[a] = std::max(reached.hi[a], had.hi[a]);
            }
          }
          word = packBrickBox(reached);
        }
      });
  return out;
}

std::vector<uint32_t> dualBrickIndices(const BrickRange& occupied,
                                       std::span<const uint32_t> brickIndex) {
  const BrickRange dual = dualBrickRange(occupied);
  std::vector<uint32_t> out(4 * dual.count(), 0xFFFFFFFFu);  // every brick empty
  for (uint32_t z = 0; z < dual.size[2]; ++z)
    for (uint32_t y = 0; y < dual.size[1]; ++y)
      for (uint32_t x = 0; x < dual.size[0]; ++x) {
        uint32_t* words = &out[4 * dual.local(dual.lo[0] + x, dual.lo[1] + y, dual.lo[2] + z)];
        for (uint32_t m = 0; m < 8; ++m) {
          // Dual cell c holds dual brick c - 1; its brick m is c - 1 + offset(m), which lies in
          // `occupied` (local coordinates from 0) when x - 1 + (m & 1) is in [0, size) per axis.
          const int64_t b[3] = {int64_t(x) - 1 + (m & 1), int64_t(y) - 1 + ((m >> 1) & 1),
                                int64_t(z) - 1 + (m >> 2)};
          bool inside = true;
          for (int a = 0; a < 3; ++a) inside = inside && b[a] >= 0 && b[a] < occupied.size[a];
          if (!inside) continue;
          const uint32_t k = brickIndex[occupied.local(occupied.lo[0] + b[0], occupied.lo[1] + b[1],
                                                       occupied.lo[2] + b[2])];
          if (k == kEmptyBrick) continue;
          VOXLINK_DCHECK(k < kEmptyBrick16);
          const uint32_t shift = 16 * (m & 1);
          words[m >> 1] = (words[m >> 1] & ~(0xFFFFu << shift)) | (k << shift);
        }
      }
  return out;
}

}  // namespace voxlink::render
