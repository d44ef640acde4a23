// SPDX-License-Identifier: BSD-3-Clause
// Byte swapping for sources written with the other byte order.
#pragma once

#include <cstddef>
#include <cstdint>

namespace voxlink::sources {

constexpr bool kHostIsLittleEndian = __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__;

// Reverses the bytes of each of `count` elements of `elementBytes` (1, 2, 4 or 8) in place.
void swapBytesInPlace(void* data, size_t count, size_t elementBytes);

}  // namespace voxlink::sources
