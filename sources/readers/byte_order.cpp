// SPDX-License-Identifier: BSD-3-Clause
#include "sources/readers/detail/byte_order.h"

#include <cstring>

namespace voxlink::sources {
namespace {

uint16_t byteSwapped(uint16_t v) { return __builtin_bswap16(v); }
uint32_t byteSwapped(uint32_t v) { return __builtin_bswap32(v); }
uint64_t byteSwapped(uint64_t v) { return __builtin_bswap64(v); }

// Elements of type T at p need not be aligned: each goes through memcpy.
template <class T>
void swapEach(uint8_t* p, size_t count) {
  for (size_t i = 0; i < count; ++i) {
    T v;
    std::memcpy(&v, p + sizeof(T) * i, sizeof(T));
    v = byteSwapped(v);
    std::memcpy(p + sizeof(T) * i, &v, sizeof(T));
  }
}

}  // namespace

void swapBytesInPlace(void* data, size_t count, size_t elementBytes) {
  auto* p = static_cast<uint8_t*>(data);
  switch (elementBytes) {
    case 2:
      swapEach<uint16_t>(p, count);
      break;
    case 4:
      swapEach<uint32_t>(p, count);
      break;
    case 8:
      swapEach<uint64_t>(p, count);
      break;
    default:
      break;
  }
}

}  // namespace voxlink::sources
