// SPDX-License-Identifier: BSD-3-Clause
#include "render/gl/detail/gradient_directions.h"

#include <cmath>

#include "format/gradient_codec.h"

namespace voxlink::render::gl {

namespace {

uint32_t signed10(float v) { return uint32_t(int32_t(std::lround(v * 511.0f))) & 0x3FFu; }

}  // namespace

uint32_t packGradientDirection(uint16_t code) {
  const auto v = format::decodeGradient(code);
  return signed10(v[0]) | signed10(v[1]) << 10 | signed10(v[2]) << 20;
}

std::vector<uint32_t> packGradientDirections(std::span<const uint8_t> codes) {
  std::vector<uint32_t> words(codes.size() / 2);
  // Codes repeat (65,536 possible), so a table of all of them is cheaper than decoding each.
  std::vector<uint32_t> table(1u << 16);
  for (uint32_t c = 0; c < table.size(); ++c) table[c] = packGradientDirection(uint16_t(c));
  for (size_t i = 0; i < words.size(); ++i)
    words[i] = table[uint16_t(codes[2 * i] | codes[2 * i + 1] << 8)];
  return words;
}

}  // namespace voxlink::render::gl
