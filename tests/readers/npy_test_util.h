// SPDX-License-Identifier: BSD-3-Clause
// Writes .npy files byte by byte from the format's specification (numpy is not installed):
// magic, version, little-endian header length, a padded dict literal ending in '\n', data.
#pragma once

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

namespace voxlink::testing {

inline std::vector<uint8_t> npyBytes(int major, const std::string& dict,
                                     const std::vector<uint8_t>& data, size_t align = 64) {
  const size_t lengthBytes = major == 1 ? 2 : 4;
  std::string header = dict;
  const size_t fixed = 8 + lengthBytes;
  while ((fixed + header.size() + 1) % align != 0) header += ' ';
  header += '\n';
  std::vector<uint8_t> out = {0x93, 'N', 'U', 'M', 'P', 'Y', static_cast<uint8_t>(major), 0};
  for (size_t i = 0; i < lengthBytes; ++i)
    out.push_back(static_cast<uint8_t>((header.size() >> (8 * i)) & 0xff));
  out.insert(out.end(), header.begin(), header.end());
  out.insert(out.end(), data.begin(), data.end());
  return out;
}

// Element bytes of value v as `size`-byte integer or float, in the given byte order.
template <class T>
void appendValue(std::vector<uint8_t>& out, T v, bool bigEndian) {
  uint8_t b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));
  if (bigEndian)
    for (size_t i = sizeof(T); i-- > 0;) out.push_back(b[i]);
  else
    for (size_t i = 0; i < sizeof(T); ++i) out.push_back(b[i]);
}

}  // namespace voxlink::testing
