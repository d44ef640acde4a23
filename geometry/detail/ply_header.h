// SPDX-License-Identifier: BSD-3-Clause
// A PLY file's header: its encoding, its elements with their counts and properties, and where
// the data starts. One parser for the checks run before assimp (mesh_file_checks), the strip
// reader (ply_strips) and the face count a load is compared with.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "base/error.h"

namespace voxlink::geometry {

enum class PlyEncoding { kAscii, kLittle, kBig };

struct PlyProperty {
  std::string name, type;  // a list: `type` of its items, `countType` of its length
  std::string countType;
  bool list = false;
};

struct PlyElement {
  std::string name;
  uint64_t count = 0;
  std::vector<PlyProperty> properties;
};

struct PlyHeader {
  PlyEncoding encoding = PlyEncoding::kAscii;
  std::vector<PlyElement> elements;
  size_t dataStart = 0;  // the byte after end_header's line end

  const PlyElement* find(const std::string& name) const;  // null when the header has none
};

// Reads the header from the file's first limits::kMaxTextHeaderBytes. Errors name the file and
// the field: no `end_header` line, a format PLY does not have, an element count that is not a
// whole number. Property types are kept as written; plyTypeBytes says whether PLY knows them
// (assimp knows a few more, so the caller decides).
Result<PlyHeader> readPlyHeader(const std::string& path);

// Bytes of one PLY scalar type (`uchar`, `int32`, `float`, ...); 0 for a name PLY does not have.
uint64_t plyTypeBytes(const std::string& type);

}  // namespace voxlink::geometry
