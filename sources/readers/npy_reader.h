// SPDX-License-Identifier: BSD-3-Clause
// NumPy .npy arrays (format versions 1.0, 2.0 and 3.0), 1-D to 3-D (leading axes of size 1
// are allowed beyond that), dtypes u1 i1 u2 i2 u4 i4 f4 f8 in either byte order.
//
// Axis convention: the logical array a[z][y][x] (shape (nz, ny, nx), 2-D (ny, nx), 1-D (nx))
// is the volume, whatever the memory order: np.save(a) and np.save(np.asfortranarray(a)) give
// the same volume. C-order native-endian files are mapped and served zero-copy like raw
// files; Fortran-order files are gathered from the mapping (each read touches the whole file,
// so read in large slabs).
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <string>

#include "sources/volume_source.h"

namespace voxlink::sources {

struct NpyHeader {
  int majorVersion = 1, minorVersion = 0;
  uint64_t dataOffset = 0;  // bytes before the array data
  std::string descr;        // as written, e.g. "<f8"
  ScalarType type = ScalarType::kU8;
  Endian endian = Endian::kLittle;
  bool fortranOrder = false;
  std::vector<uint64_t> shape;            // as written
  std::array<uint32_t, 3> dims{1, 1, 1};  // x, y, z
};

// Parses and checks the header of `bytes` (the file's first `size` bytes); `path` names the
// file in messages.
Result<NpyHeader> parseNpyHeader(const uint8_t* bytes, uint64_t size, const std::string& path);

Result<std::unique_ptr<VolumeSource>> openNpy(const std::string& path, const OpenOptions& options);

// True when the file starts with the .npy magic string.
bool hasNpyMagic(const std::string& path);

}  // namespace voxlink::sources
