#include "format/derived_sections.h"

#include <bit>
#include <cstring>
#include <vector>

#include "format/brick_rows.h"
#include "format/layout.h"

namespace voxlink::format {
namespace {

// The number of bricks `masks` holds, or an error when it is not whole bricks or does not
// match the `expected` count derived from the target's size.
Result<uint64_t> brickCount(std::span<const uint8_t> masks, uint32_t n, uint64_t expected,
                            bool sizeFits, const std::string& where) {
  const uint64_t brickBytes = uint64_t{maskWordsPerBrick(n)} * 4;
  if (n == 0 || brickBytes == 0 || masks.size() % brickBytes != 0 || !sizeFits ||
      masks.size() / brickBytes != expected)
    return makeError(ErrorCode::kCorrupt, where, ": derived from MASK: ", masks.size(),
                     " bytes of masks do not hold the ", expected, " bricks its size needs");
  return expected;
}

}  // namespace

Status deriveRowStarts(std::span<const uint8_t> masks, uint32_t n, std::span<uint8_t> rowStarts,
                       const std::string& where) {
  const uint64_t rowBytes = uint64_t{n} * n * 2;
  const bool fits = n > 0 && rowStarts.size() % rowBytes == 0;
  VOXLINK_ASSIGN_OR_RETURN(
      const uint64_t bricks,
      brickCount(masks, n, fits ? rowStarts.size() / rowBytes : 0, fits, where));
  const uint32_t words = maskWordsPerBrick(n);
  std::vector<uint32_t> mask(words);
  std::vector<uint16_t> starts(size_t{n} * n);
  for (uint64_t k = 0; k < bricks; ++k) {
    std::memcpy(mask.data(), masks.data() + k * words * 4, words * 4);
    rowStartsFromMasks(mask.data(), n, starts.data());
    std::memcpy(rowStarts.data() + k * rowBytes, starts.data(), rowBytes);
  }
  return Status::ok();
}

Status deriveBrickVoxelBase(std::span<const uint8_t> masks, uint32_t n,
                            std::span<uint8_t> brickBase, const std::string& where) {
  const bool fits = brickBase.size() >= 4 && brickBase.size() % 4 == 0;
  VOXLINK_ASSIGN_OR_RETURN(const uint64_t bricks,
                           brickCount(masks, n, fits ? brickBase.size() / 4 - 1 : 0, fits, where));
  const uint64_t brickBytes = uint64_t{maskWordsPerBrick(n)} * 4;
  uint32_t base = 0;  // wraps only for masks no valid file has; the checksum refuses those
  for (uint64_t k = 0; k <= bricks; ++k) {
    std::memcpy(brickBase.data() + 4 * k, &base, 4);
    if (k == bricks) break;
    for (uint64_t at = k * brickBytes; at < (k + 1) * brickBytes; at += 4) {
      uint32_t word;
      std::memcpy(&word, masks.data() + at, 4);
      base += static_cast<uint32_t>(std::popcount(word));
    }
  }
  return Status::ok();
}

}  // namespace voxlink::format
