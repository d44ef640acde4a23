// SPDX-License-Identifier: BSD-3-Clause
#include "geometry/detail/mesh_file_checks.h"

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string_view>

#include "base/limits.h"

namespace voxlink::geometry {
namespace {

uint64_t fileBytes(const std::string& path) {
  std::error_code ec;
  const auto size = std::filesystem::file_size(path, ec);
  return ec ? 0 : uint64_t(size);
}

// The OFF keyword with assimp's optional prefixes (ST, C, N, 4, n), or npos.
size_t offKeywordLength(std::string_view token) {
  size_t at = 0;
  if (token.substr(at, 2) == "ST") at += 2;
  for (char prefix : {'C', 'N', '4', 'n'})
    if (at < token.size() && token[at] == prefix) ++at;
  return token.substr(at) == "OFF" ? at + 3 : std::string_view::npos;
}

// The next line that holds more than spaces and is no '#' comment.
bool nextDataLine(std::istream& in, std::string& line, uint64_t& number) {
  while (std::getline(in, line)) {
    ++number;
    const size_t first = line.find_first_not_of(" \t\r");
    if (first != std::string::npos && line[first] != '#') return true;
  }
  return false;
}

}  // namespace

std::string readFileHead(const std::string& path, size_t bytes) {
  std::ifstream in(path, std::ios::binary);
  std::string head(bytes, '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<size_t>(in.gcount()));
  return head;
}

bool looksLikePly(const std::string& path) {
  const std::string magic = readFileHead(path, 4);
  return magic.size() == 4 && magic.compare(0, 3, "ply") == 0 &&
         (magic[3] == '\n' || magic[3] == '\r');
}

bool looksLikeOff(const std::string& path) {
  std::istringstream head(readFileHead(path, 16));
  std::string token;
  head >> token;
  return offKeywordLength(token) != std::string_view::npos;
}

Status checkPlyFile(const std::string& path, const PlyHeader& header) {
  // Each element's count times the least bytes one item takes must fit in the data: binary, the
  // scalars and list counts (lists may be empty); ASCII, a character and a separator per value.
  const bool ascii = header.encoding == PlyEncoding::kAscii;
  const uint64_t fileSize = fileBytes(path);
  const uint64_t dataBytes = fileSize - std::min<uint64_t>(fileSize, header.dataStart);
  // ASCII: the last value needs no separator after it.
  uint64_t left = dataBytes + (ascii ? 1 : 0);
  bool earlier = false;  // elements before this one took bytes
  for (const PlyElement& e : header.elements) {
    uint64_t itemBytes = 0;
    for (const PlyProperty& p : e.properties) {
      const uint64_t bytes = plyTypeBytes(p.list ? p.countType : p.type);
      if (bytes == 0) return Status::ok();  // a type assimp may know; its own error then
      itemBytes += ascii ? 2 : bytes;
    }
    itemBytes = std::max<uint64_t>(itemBytes, 1);
    if (e.count > left / itemBytes)
      return makeError(ErrorCode::kCorrupt, path, ": element ", e.name, " ", e.count,
                       ": needs at least ", e.count, " x ", itemBytes, " bytes, but the file has ",
                       std::min(left, dataBytes), " after its header",
                       earlier ? " and the elements before" : "");
    left -= e.count * itemBytes;
    earlier = earlier || e.count > 0;
  }
  return Status::ok();
}

Status checkOffFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::string line;
  uint64_t number = 0;
  if (!nextDataLine(in, line, number)) return Status::ok();  // assimp names the empty file
  std::istringstream header(line);
  std::string token;
  header >> token;
  if (offKeywordLength(token) == std::string::npos) return Status::ok();
  if (token.find('n') != std::string::npos) return Status::ok();  // nOFF: a dimension first
  // The counts follow the keyword on its line or on the next data line.
  uint64_t vertices = 0, faces = 0;
  if (!(header >> vertices >> faces)) {
    if (!nextDataLine(in, line, number)) return Status::ok();
    std::istringstream counts(line);
    if (!(counts >> vertices >> faces))
      return makeError(ErrorCode::kCorrupt, path, ": line ", number,
                       ": expected the vertex and face counts");
  }
  // A vertex line holds at least "0 0 0\n", a face line "1 0\n" (assimp takes 1 to 9 corners).
  const uint64_t bytes = fileBytes(path);
  if (vertices > bytes / 6 || faces > bytes / 4 || vertices * 6 + faces * 4 > bytes)
    return makeError(ErrorCode::kCorrupt, path, ": header claims ", vertices, " vertices and ",
                     faces, " faces; a file of ", bytes, " bytes holds fewer");
  for (uint64_t v = 0; v < vertices; ++v)
    if (!nextDataLine(in, line, number))
      return makeError(ErrorCode::kCorrupt, path, ": vertex ", v, ": missing (the header claims ",
                       vertices, ")");
  for (uint64_t f = 0; f < faces; ++f) {
    if (!nextDataLine(in, line, number))
      return makeError(ErrorCode::kCorrupt, path, ": face ", f, ": missing (the header claims ",
                       faces, ")");
    std::istringstream face(line);
    uint64_t corners = 0;
    face >> corners;
    for (uint64_t c = 0; c < corners; ++c) {
      int64_t index = -1;
      if (!(face >> index)) break;  // assimp's own error for a short face
      if (index < 0 || uint64_t(index) >= vertices)
        return makeError(ErrorCode::kCorrupt, path, ": line ", number, ": face ", f,
                         ": vertex index ", index, " outside the ", vertices, " vertices");
    }
  }
  return Status::ok();
}

uint64_t declaredOffFaceCount(const std::string& path) {
  if (!looksLikeOff(path)) return 0;
  std::ifstream in(path, std::ios::binary);
  std::string line, token;
  uint64_t number = 0, vertices = 0, faces = 0;
  if (!nextDataLine(in, line, number)) return 0;
  std::istringstream first(line);
  first >> token;
  if (token.find('n') != std::string::npos) return 0;  // nOFF: a dimension first
  if (first >> vertices >> faces) return faces;
  if (!nextDataLine(in, line, number)) return 0;
  std::istringstream counts(line);
  return counts >> vertices >> faces ? faces : 0;
}

}  // namespace voxlink::geometry
