// SPDX-License-Identifier: BSD-3-Clause
#include "format/derived_sections.h"

#include <algorithm>
#include <atomic>
#include <bit>
#include <cstring>
#include <vector>

#include "base/parallel_for.h"
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

// The bricks whose row starts fill `rowStartBytes`, or an error when that is not whole bricks
// or not as many as `masks` holds.
Result<uint64_t> rowStartBricks(std::span<const uint8_t> masks, uint32_t n, uint64_t rowStartBytes,
                                const std::string& where) {
  const uint64_t rowBytes = uint64_t{n} * n * 2;
  const bool fits = n > 0 && rowStartBytes % rowBytes == 0;
  return brickCount(masks, n, fits ? rowStartBytes / rowBytes : 0, fits, where);
}

// The row starts of one brick at a time, from its mask words (copied: MASK need not be aligned).
class BrickRows {
 public:
  explicit BrickRows(uint32_t n) : n_(n), mask_(maskWordsPerBrick(n)), starts_(size_t{n} * n) {}
  const uint16_t* startsOf(std::span<const uint8_t> masks, uint64_t k) {
    std::memcpy(mask_.data(), masks.data() + k * mask_.size() * 4, mask_.size() * 4);
    rowStartsFromMasks(mask_.data(), n_, starts_.data());
    return starts_.data();
  }

 private:
  uint32_t n_;
  std::vector<uint32_t> mask_;
  std::vector<uint16_t> starts_;
};

// Runs fn(begin, end) over ranges of `bricks` on `threads` threads; whether every call returned
// true.
template <class Fn>
bool forEachBrickRange(uint64_t bricks, unsigned threads, Fn&& fn) {
  constexpr uint64_t kRange = 4096;
  std::atomic<bool> all{true};
  parallelFor((bricks + kRange - 1) / kRange, threads, [&](uint64_t r) {
    if (all.load(std::memory_order_relaxed) && !fn(r * kRange, std::min(bricks, (r + 1) * kRange)))
      all = false;
  });
  return all;
}

}  // namespace

Status deriveRowStarts(std::span<const uint8_t> masks, uint32_t n, std::span<uint8_t> rowStarts,
                       const std::string& where, unsigned threads) {
  const uint64_t rowBytes = uint64_t{n} * n * 2;
  VOXLINK_ASSIGN_OR_RETURN(const uint64_t bricks,
                           rowStartBricks(masks, n, rowStarts.size(), where));
  forEachBrickRange(bricks, threads, [&](uint64_t begin, uint64_t end) {
    BrickRows rows(n);
    for (uint64_t k = begin; k < end; ++k)
      std::memcpy(rowStarts.data() + k * rowBytes, rows.startsOf(masks, k), rowBytes);
    return true;
  });
  return Status::ok();
}

bool rowStartsMatch(std::span<const uint8_t> masks, uint32_t n, std::span<const uint8_t> rowStarts,
                    unsigned threads) {
  const uint64_t rowBytes = uint64_t{n} * n * 2;
  auto bricks = rowStartBricks(masks, n, rowStarts.size(), "");
  if (!bricks) return false;
  return forEachBrickRange(*bricks, threads, [&](uint64_t begin, uint64_t end) {
    BrickRows rows(n);
    for (uint64_t k = begin; k < end; ++k)
      if (std::memcmp(rowStarts.data() + k * rowBytes, rows.startsOf(masks, k), rowBytes) != 0)
        return false;
    return true;
  });
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
