// SPDX-License-Identifier: BSD-3-Clause
// A strict hand parser for NRRD headers (NRRD0001..NRRD0005, attached or detached), after the
// teem format specification: field names in all the spellings teem accepts, data file lists,
// line/byte skips. Only what a 3-D scalar volume needs is kept; fields that would change the
// meaning of the data and are not supported give kUnsupported naming the field.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "base/error.h"
#include "format/scalar_type.h"
#include "sources/readers/detail/axes.h"
#include "sources/readers/detail/data_pieces.h"

namespace voxlink::sources {

struct NrrdHeader {
  int version = 0;  // the digit of NRRD000X
  int dimension = 0;
  ScalarType type = ScalarType::kU8;
  std::vector<uint64_t> sizes;
  std::vector<double> spacings;                 // empty when absent
  std::vector<std::optional<Vec3>> directions;  // per axis; nullopt for "none"; empty when absent
  std::optional<Vec3> origin;                   // space origin
  PieceEncoding encoding = PieceEncoding::kRaw;
  std::optional<Endian> endian;
  uint64_t lineSkip = 0;
  int64_t byteSkip = 0;                // -1: raw data is the end of the file
  std::vector<std::string> dataFiles;  // paths, resolved beside the header
  int dataFileSubdim = 0;              // the optional <subdim> of a file list
  bool attached = false;
  uint64_t dataOffset = 0;                 // attached: first byte after the blank line
  std::vector<std::string> ignoredFields;  // recognized, not needed for a scalar volume
};

// Parses the header of `path` (.nrrd or .nhdr).
Result<NrrdHeader> parseNrrdHeader(const std::string& path);

// NRRD type names ("uchar", "unsigned char", "uint8", "short", ...), case-insensitive.
// nullopt for unknown names; kUnsupported for 64-bit integers and "block" is the caller's job.
std::optional<ScalarType> nrrdTypeFromName(const std::string& name);

}  // namespace voxlink::sources
