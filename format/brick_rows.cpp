// SPDX-License-Identifier: BSD-3-Clause
#include "format/brick_rows.h"

namespace voxlink::format {

uint32_t rowStartsFromMasks(const uint32_t* brickMask, uint32_t n, uint16_t* rowStarts) {
  uint32_t count = 0;
  for (uint32_t row = 0; row < n * n; ++row) {
    rowStarts[row] = static_cast<uint16_t>(count);
    count += static_cast<uint32_t>(std::popcount(rowBits(brickMask, n, row)));
  }
  return count;
}

}  // namespace voxlink::format
