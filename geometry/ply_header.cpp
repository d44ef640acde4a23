// SPDX-License-Identifier: BSD-3-Clause
#include "geometry/detail/ply_header.h"

#include <sstream>

#include "base/limits.h"
#include "geometry/detail/mesh_file_checks.h"

namespace voxlink::geometry {
namespace {

// The offset just past the line `end_header` and any spaces or tabs after it (before its line
// end), or npos. Trailing blanks occur in files written by hand and assimp reads them.
size_t endOfHeaderLine(const std::string& head) {
  for (size_t at = head.find("\nend_header"); at != std::string::npos;
       at = head.find("\nend_header", at + 1)) {
    size_t after = at + 11;
    while (after < head.size() && (head[after] == ' ' || head[after] == '\t')) ++after;
    if (after == head.size() || head[after] == '\n' || head[after] == '\r') return after;
  }
  return std::string::npos;
}

}  // namespace

const PlyElement* PlyHeader::find(const std::string& name) const {
  for (const PlyElement& e : elements)
    if (e.name == name) return &e;
  return nullptr;
}

Result<PlyHeader> readPlyHeader(const std::string& path) {
  const std::string head = readFileHead(path, limits::kMaxTextHeaderBytes);
  const size_t end = endOfHeaderLine(head);
  if (end == std::string::npos)
    return makeError(ErrorCode::kCorrupt, path, ": PLY header has no 'end_header' line",
                     head.size() == limits::kMaxTextHeaderBytes ? " in its first 1 MiB" : "");
  PlyHeader header;
  header.dataStart = end;
  if (header.dataStart < head.size() && head[header.dataStart] == '\r') ++header.dataStart;
  if (header.dataStart < head.size() && head[header.dataStart] == '\n') ++header.dataStart;
  std::istringstream lines(head.substr(0, end));
  std::string line;
  for (size_t number = 1; std::getline(lines, line); ++number) {
    std::istringstream words(line);
    std::string keyword;
    words >> keyword;
    if (keyword == "format") {
      std::string kind;
      words >> kind;
      if (kind == "binary_little_endian")
        header.encoding = PlyEncoding::kLittle;
      else if (kind == "binary_big_endian")
        header.encoding = PlyEncoding::kBig;
      else if (kind != "ascii")
        return makeError(ErrorCode::kCorrupt, path, ": line ", number, ": format '", kind,
                         "' is not a PLY format");
    } else if (keyword == "element") {
      PlyElement e;
      std::string count;
      words >> e.name >> count;
      if (count.empty() || count.find_first_not_of("0123456789") != std::string::npos ||
          count.size() > 19)
        return makeError(ErrorCode::kCorrupt, path, ": line ", number, ": element ", e.name,
                         ": count '", count, "' is not a whole number");
      e.count = std::stoull(count);
      // assimp 5.2 sizes its vertex array by the first `vertex` element, and the vertices of a
      // second one were written past its end (heap corruption, found by the mesh fuzz target).
      if (header.find(e.name) != nullptr)
        return makeError(ErrorCode::kCorrupt, path, ": line ", number, ": element ", e.name,
                         " is declared a second time");
      header.elements.push_back(e);
    } else if (keyword == "property" && !header.elements.empty()) {
      PlyProperty p;
      words >> p.type;
      if (p.type == "list") {
        p.list = true;
        words >> p.countType >> p.type;
      }
      words >> p.name;
      header.elements.back().properties.push_back(p);
    }
  }
  return header;
}

uint64_t plyTypeBytes(const std::string& type) {
  if (type == "char" || type == "uchar" || type == "int8" || type == "uint8") return 1;
  if (type == "short" || type == "ushort" || type == "int16" || type == "uint16") return 2;
  if (type == "int" || type == "uint" || type == "int32" || type == "uint32" || type == "float" ||
      type == "float32")
    return 4;
  if (type == "double" || type == "float64") return 8;
  return 0;
}

}  // namespace voxlink::geometry
