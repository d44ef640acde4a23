// SPDX-License-Identifier: BSD-3-Clause
#include "render/gl/detail/voxel_words.h"

#include <cmath>

#include "format/gradient_codec.h"

namespace voxlink::render::gl {

namespace {

uint32_t signed8(float v) { return uint32_t(int32_t(std::lround(v * 127.0f))) & 0xFFu; }

}  // namespace

uint32_t packGradientDirection(uint16_t code) {
  const auto v = format::decodeGradient(code);
  return signed8(v[0]) | signed8(v[1]) << 8 | signed8(v[2]) << 16;
}

std::vector<uint32_t> packVoxelWords(std::span<const uint8_t> codes,
                                     std::span<const uint8_t> values8) {
  std::vector<uint32_t> words(codes.size() / 2);
  // Codes repeat (65,536 possible), so a table of all of them is cheaper than decoding each.
  std::vector<uint32_t> table(1u << 16);
  for (uint32_t c = 0; c < table.size(); ++c) table[c] = packGradientDirection(uint16_t(c));
  const bool withValues = values8.size() >= words.size();
  for (size_t i = 0; i < words.size(); ++i) {
    words[i] = table[uint16_t(codes[2 * i] | codes[2 * i + 1] << 8)];
    if (withValues) words[i] |= uint32_t(values8[i]) << 24;
  }
  return words;
}

}  // namespace voxlink::render::gl
