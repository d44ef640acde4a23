// SPDX-License-Identifier: BSD-3-Clause
#include "render/brick_bounds.h"

#include <algorithm>
#include <bit>

#include "format/layout.h"

namespace voxlink::render {

uint32_t packBrickBox(const BrickBox& b) {
  uint32_t w = 0;
  for (int a = 0; a < 3; ++a) w |= (b.lo[a] & 31u) << (5 * a) | (b.hi[a] & 31u) << (15 + 5 * a);
  return w;
}

BrickBox unpackBrickBox(uint32_t w) {
  BrickBox b;
  for (int a = 0; a < 3; ++a) {
    b.lo[a] = (w >> (5 * a)) & 31u;
    b.hi[a] = (w >> (15 + 5 * a)) & 31u;
  }
  return b;
}

std::vector<uint32_t> brickBounds(const format::VoxLinkFile& file) {
  const uint32_t n = file.brickSize();
  const uint64_t bricks = file.occupiedBrickCount();
  const auto masks = file.rowMaskWords();
  const uint32_t wordsPerBrick = format::maskWordsPerBrick(n);
  const format::AxisFrame f = format::axisFrame(file.predominantAxis());
  const uint32_t rowMask = n == 32 ? 0xFFFFFFFFu : (1u << n) - 1u;
  std::vector<uint32_t> out(bricks);
  for (uint64_t k = 0; k < bricks; ++k) {
    BrickBox box{{n, n, n}, {0, 0, 0}};
    const uint32_t* words = masks.data() + k * wordsPerBrick;
    for (uint32_t row = 0; row < n * n; ++row) {
      const uint32_t bit = row * n;
      const uint32_t bits = (words[bit >> 5] >> (bit & 31)) & rowMask;
      if (bits == 0) continue;
      const uint32_t u = row % n, v = row / n;
      const uint32_t d0 = static_cast<uint32_t>(std::countr_zero(bits));
      const uint32_t d1 = 31u - static_cast<uint32_t>(std::countl_zero(bits));
      box.lo[f.u] = std::min(box.lo[f.u], u);
      box.hi[f.u] = std::max(box.hi[f.u], u);
      box.lo[f.v] = std::min(box.lo[f.v], v);
      box.hi[f.v] = std::max(box.hi[f.v], v);
      box.lo[f.w] = std::min(box.lo[f.w], d0);
      box.hi[f.w] = std::max(box.hi[f.w], d1);
    }
    out[k] = packBrickBox(box);
  }
  return out;
}

}  // namespace voxlink::render
