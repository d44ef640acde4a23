// SPDX-License-Identifier: BSD-3-Clause
// Overflow-checked size arithmetic for sizes that come from files or the command line: every
// product or sum of such sizes goes through these before it sizes a buffer or an offset.
#pragma once

#include <cstdint>
#include <initializer_list>
#include <optional>

namespace voxlink {
inline namespace base {

// a * b, or nullopt when it does not fit in 64 bits.
constexpr std::optional<uint64_t> checkedMul(uint64_t a, uint64_t b) {
  uint64_t r = 0;
  if (__builtin_mul_overflow(a, b, &r)) return std::nullopt;
  return r;
}

// a + b, or nullopt when it does not fit in 64 bits.
constexpr std::optional<uint64_t> checkedAdd(uint64_t a, uint64_t b) {
  uint64_t r = 0;
  if (__builtin_add_overflow(a, b, &r)) return std::nullopt;
  return r;
}

// The product of all factors, or nullopt on overflow.
constexpr std::optional<uint64_t> checkedProduct(std::initializer_list<uint64_t> factors) {
  uint64_t r = 1;
  for (uint64_t f : factors) {
    const auto next = checkedMul(r, f);
    if (!next) return std::nullopt;
    r = *next;
  }
  return r;
}

}  // namespace base
}  // namespace voxlink
