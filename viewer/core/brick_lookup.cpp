#include "viewer/core/brick_lookup.h"

#include <algorithm>

#include "viewer/core/brick_bounds.h"

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

std::vector<uint32_t> dualBrickBoxes(const format::FileHeader& h, std::span<const uint32_t> index,
                                     std::span<const uint32_t> brickBoxes) {
  const int64_t n = h.brickSize;
  const std::array<uint32_t, 3> dual = dualBrickGrid(h);
  struct Cells {
    int64_t lo[3], hi[3];
  };
  std::vector<Cells> boxes(uint64_t{dual[0]} * dual[1] * dual[2], Cells{{n, n, n}, {-1, -1, -1}});
  // An occupied brick b is read by the dual bricks b - 1 and b per axis (dual cells b, b + 1).
  for (uint64_t z = 0, b = 0; z < h.brickGrid[2]; ++z)
    for (uint64_t y = 0; y < h.brickGrid[1]; ++y)
      for (uint64_t x = 0; x < h.brickGrid[0]; ++x, ++b) {
        if (index[b] == kEmptyBrick) continue;
        const BrickBox box = unpackBrickBox(brickBoxes[index[b]]);
        const uint64_t brick[3] = {x, y, z};
        for (uint64_t m = 0; m < 8; ++m) {
          const uint64_t c[3] = {x + (m & 1), y + ((m >> 1) & 1), z + (m >> 2)};  // dual cell
          // Cells reached, global: [b n + lo - 1, b n + hi]; the dual brick's: [(c - 1) n, c n -
          // 1].
          Cells reached;
          bool any = true;
          for (int a = 0; a < 3; ++a) {
            const int64_t origin = (int64_t(c[a]) - 1) * n;
            reached.lo[a] = std::max(int64_t(brick[a]) * n + box.lo[a] - 1 - origin, int64_t{0});
            reached.hi[a] = std::min(int64_t(brick[a]) * n + box.hi[a] - origin, n - 1);
            any = any && reached.lo[a] <= reached.hi[a];
          }
          if (!any) continue;
          Cells& cells = boxes[(c[2] * dual[1] + c[1]) * dual[0] + c[0]];
          for (int a = 0; a < 3; ++a) {
            cells.lo[a] = std::min(cells.lo[a], reached.lo[a]);
            cells.hi[a] = std::max(cells.hi[a], reached.hi[a]);
          }
        }
      }
  std::vector<uint32_t> out(boxes.size(), kEmptyDualBrick);
  for (size_t i = 0; i < boxes.size(); ++i) {
    const Cells& c = boxes[i];
    if (c.hi[0] < c.lo[0] || c.hi[1] < c.lo[1] || c.hi[2] < c.lo[2]) continue;
    BrickBox box;
    for (int a = 0; a < 3; ++a) {
      box.lo[a] = uint32_t(c.lo[a]);
      box.hi[a] = uint32_t(c.hi[a]);
    }
    out[i] = packBrickBox(box);
  }
  return out;
}

}  // namespace voxlink::viewer
