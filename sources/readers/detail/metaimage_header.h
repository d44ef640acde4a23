// SPDX-License-Identifier: BSD-3-Clause
// A hand parser for MetaImage headers (.mhd detached, .mha with LOCAL data): "Key = Value" lines
// ending with ElementDataFile. Keys MetaIO uses for things a scalar volume does not need
// (AnatomicalOrientation, CenterOfRotation, ElementMin, ...) are ignored.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "base/error.h"
#include "format/scalar_type.h"
#include "sources/readers/detail/axes.h"
#include "sources/readers/detail/data_pieces.h"

namespace voxlink::sources {

struct MetaImageHeader {
  int ndims = 0;
  std::vector<uint64_t> dimSize;
  ScalarType type = ScalarType::kU8;
  std::vector<double> spacing;  // ElementSpacing, else ElementSize, else empty
  bool spacingFromElementSize = false;
  std::optional<Vec3> offset;               // Offset / Origin / Position
  std::optional<std::array<Vec3, 3>> axes;  // TransformMatrix / Rotation / Orientation rows
  Endian endian = Endian::kLittle;
  bool compressed = false;
  std::optional<uint64_t> compressedSize;  // CompressedDataSize
  int64_t headerSize = 0;                  // bytes before the data in each data file; -1: at end
  bool local = false;                      // ElementDataFile = LOCAL
  uint64_t localOffset = 0;                // LOCAL: first byte after the ElementDataFile line
  std::vector<std::string> dataFiles;      // paths beside the header
};

Result<MetaImageHeader> parseMetaImageHeader(const std::string& path);

}  // namespace voxlink::sources
