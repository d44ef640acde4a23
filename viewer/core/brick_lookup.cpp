#include "viewer/core/brick_lookup.h"

namespace voxlink::viewer {

std::vector<uint32_t> occupiedIndexByBrick(const format::VoxLinkFile& file) {
  const auto occupancy = file.occupancyWords();
  std::vector<uint32_t> out(file.gridBrickCount(), kEmptyBrick);
  uint32_t k = 0;
  for (uint64_t b = 0; b < out.size(); ++b)
    if ((occupancy[b >> 5] >> (b & 31)) & 1u) out[b] = k++;
  return out;
}

std::array<uint32_t, 3> dualBrickGrid(const format::FileHeader& h) {
  return {h.brickGrid[0] + 1, h.brickGrid[1] + 1, h.brickGrid[2] + 1};
}

std::vector<uint32_t> dualBrickOccupancy(const format::VoxLinkFile& file) {
  const auto& h = file.header();
  const auto occupancy = file.occupancyWords();
  const std::array<uint64_t, 3> g{h.brickGrid[0], h.brickGrid[1], h.brickGrid[2]};
  const std::array<uint32_t, 3> dual = dualBrickGrid(h);
  const uint64_t dualCount = uint64_t{dual[0]} * dual[1] * dual[2];
  std::vector<uint32_t> bits((dualCount + 31) / 32, 0u);
  auto setBit = [&](uint64_t x, uint64_t y, uint64_t z) {
    const uint64_t i = (z * dual[1] + y) * dual[0] + x;
    bits[i >> 5] |= 1u << (i & 31);
  };
  // An occupied brick b is read by the dual bricks b - 1 and b per axis, at dual cells b and
  // b + 1.
  for (uint64_t z = 0, b = 0; z < g[2]; ++z)
    for (uint64_t y = 0; y < g[1]; ++y)
      for (uint64_t x = 0; x < g[0]; ++x, ++b) {
        if (!((occupancy[b >> 5] >> (b & 31)) & 1u)) continue;
        for (uint64_t m = 0; m < 8; ++m) setBit(x + (m & 1), y + ((m >> 1) & 1), z + (m >> 2));
      }
  return bits;
}

}  // namespace voxlink::viewer
