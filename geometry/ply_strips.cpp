// SPDX-License-Identifier: BSD-3-Clause
#include "geometry/detail/ply_strips.h"

#include <bit>
#include <cctype>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <utility>
#include <vector>

#include "geometry/detail/ply_header.h"

namespace voxlink::geometry {
namespace {

// The strip reader decodes every property, so it needs each type's size.
Status checkTypesKnown(const std::string& path, const PlyHeader& header) {
  for (const PlyElement& e : header.elements)
    for (const PlyProperty& p : e.properties) {
      if (p.list && plyTypeBytes(p.countType) == 0)
        return makeError(ErrorCode::kCorrupt, path, ": element ", e.name, ": list length type '",
                         p.countType, "' is not a PLY type");
      if (plyTypeBytes(p.type) == 0)
        return makeError(ErrorCode::kCorrupt, path, ": element ", e.name, ": property ", p.name,
                         ": type '", p.type, "' is not a PLY type");
    }
  return Status::ok();
}

// Reads PLY values in file order, whatever the encoding.
class ValueReader {
 public:
  ValueReader(const std::string& data, size_t at, PlyEncoding encoding)
      : data_(data), at_(at), encoding_(encoding) {}

  // False when the data ends first.
  bool next(const std::string& type, double& out) {
    if (encoding_ == PlyEncoding::kAscii) return nextText(out);
    const size_t bytes = plyTypeBytes(type);
    if (data_.size() - at_ < bytes) return false;
    uint8_t raw[8];
    std::memcpy(raw, data_.data() + at_, bytes);
    at_ += bytes;
    const bool swap =
        (encoding_ == PlyEncoding::kBig) == (std::endian::native == std::endian::little);
    if (swap)
      for (size_t i = 0; i < bytes / 2; ++i) std::swap(raw[i], raw[bytes - 1 - i]);
    out = decode(type, raw);
    return true;
  }

 private:
  bool nextText(double& out) {
    while (at_ < data_.size() && std::isspace(static_cast<unsigned char>(data_[at_]))) ++at_;
    if (at_ == data_.size()) return false;
    const char* begin = data_.c_str() + at_;
    char* stop = nullptr;
    out = std::strtod(begin, &stop);
    if (stop == begin) return false;
    at_ += static_cast<size_t>(stop - begin);
    return true;
  }

  template <class T>
  static double as(const uint8_t* raw) {
    T v;
    std::memcpy(&v, raw, sizeof v);
    return static_cast<double>(v);
  }

  static double decode(const std::string& t, const uint8_t* raw) {
    if (t == "char" || t == "int8") return as<int8_t>(raw);
    if (t == "uchar" || t == "uint8") return as<uint8_t>(raw);
    if (t == "short" || t == "int16") return as<int16_t>(raw);
    if (t == "ushort" || t == "uint16") return as<uint16_t>(raw);
    if (t == "int" || t == "int32") return as<int32_t>(raw);
    if (t == "uint" || t == "uint32") return as<uint32_t>(raw);
    if (t == "float" || t == "float32") return as<float>(raw);
    return as<double>(raw);
  }

  const std::string& data_;
  size_t at_;
  PlyEncoding encoding_;
};

// Adds the triangles of one strip, -1 restarting it.
Status addStrip(const std::vector<double>& indices, uint64_t vertices, const std::string& where,
                TriangleMesh& mesh) {
  int64_t a = -1, b = -1;
  bool flip = false;
  for (double value : indices) {
    if (value == -1) {
      a = b = -1;
      flip = false;
      continue;
    }
    // Checked as a double first: casting 1e30 or NaN to an integer is undefined.
    if (!(value >= 0 && value < double(vertices)) || value != std::floor(value))
      return makeError(ErrorCode::kCorrupt, where, ": vertex index ", value, " outside the ",
                       vertices, " vertices");
    const int64_t i = static_cast<int64_t>(value);
    if (a >= 0 && b >= 0 && a != b && b != i && a != i) {
      const uint32_t u = uint32_t(a), v = uint32_t(b), w = uint32_t(i);
      if (flip)
        mesh.triangles.insert(mesh.triangles.end(), {v, u, w});
      else
        mesh.triangles.insert(mesh.triangles.end(), {u, v, w});
    }
    if (a >= 0 && b >= 0) flip = !flip;
    a = b;
    b = i;
  }
  return Status::ok();
}

// Adds a polygon as a fan.
Status addFace(const std::vector<double>& indices, uint64_t vertices, const std::string& where,
               TriangleMesh& mesh) {
  for (double value : indices)
    if (!(value >= 0 && value < double(vertices)) || value != std::floor(value))
      return makeError(ErrorCode::kCorrupt, where, ": vertex index ", value, " outside the ",
                       vertices, " vertices");
  for (size_t k = 2; k < indices.size(); ++k)
    mesh.triangles.insert(mesh.triangles.end(),
                          {uint32_t(indices[0]), uint32_t(indices[k - 1]), uint32_t(indices[k])});
  return Status::ok();
}

}  // namespace

Result<TriangleMesh> loadPlyWithStrips(const std::string& path, const PlyHeader& header,
                                       uint64_t maxTriangles) {
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  std::string data(in ? static_cast<size_t>(in.tellg()) : 0, '\0');
  in.seekg(0);
  if (!in || !in.read(data.data(), static_cast<std::streamsize>(data.size())))
    return makeError(ErrorCode::kIo, path, ": cannot read");
  VOXLINK_RETURN_IF_ERROR(checkTypesKnown(path, header));
  ValueReader reader(data, header.dataStart, header.encoding);
  TriangleMesh mesh;
  uint64_t vertices = 0;
  bool vertexRead = false;
  std::vector<double> list;
  for (const PlyElement& e : header.elements) {
    const bool isVertex = e.name == "vertex", isStrips = e.name == "tristrips",
               isFace = e.name == "face";
    int position[3] = {-1, -1, -1}, indices = -1;
    for (size_t p = 0; p < e.properties.size(); ++p) {
      const std::string& name = e.properties[p].name;
      for (int axis = 0; axis < 3; ++axis)
        if (name == std::string(1, char('x' + axis)) && !e.properties[p].list)
          position[axis] = int(p);
      if ((name == "vertex_indices" || name == "vertex_index") && e.properties[p].list)
        indices = int(p);
    }
    if (isVertex) {
      if (position[0] < 0 || position[1] < 0 || position[2] < 0)
        return makeError(ErrorCode::kCorrupt, path, ": element vertex: no x, y and z properties");
      vertices = e.count;
      vertexRead = true;
      if (vertices > std::numeric_limits<uint32_t>::max())
        return makeError(ErrorCode::kTooLarge, path, ": ", vertices, " vertices, more than 2^32-1");
      mesh.positions.reserve(3 * vertices);
    }
    if ((isStrips || isFace) && indices < 0)
      return makeError(ErrorCode::kCorrupt, path, ": element ", e.name, ": no vertex_indices list");
    if ((isStrips || isFace) && !vertexRead)
      return makeError(ErrorCode::kCorrupt, path, ": element ", e.name,
                       " comes before the vertices");
    for (uint64_t item = 0; item < e.count; ++item) {
      const std::string where = cat(path, ": element ", e.name, " ", item);
      float xyz[3] = {0, 0, 0};
      for (size_t p = 0; p < e.properties.size(); ++p) {
        const PlyProperty& property = e.properties[p];
        double value = 0;
        if (!property.list) {
          if (!reader.next(property.type, value))
            return makeError(ErrorCode::kTruncated, where, ": data ends before property ",
                             property.name);
          for (int axis = 0; axis < 3; ++axis)
            if (int(p) == position[axis]) xyz[axis] = static_cast<float>(value);
          continue;
        }
        double length = 0;
        if (!reader.next(property.countType, length) || !(length >= 0) ||
            length != std::floor(length))
          return makeError(ErrorCode::kCorrupt, where, ": list ", property.name,
                           ": no valid length");
        list.clear();
        for (double k = 0; k < length; ++k) {
          if (!reader.next(property.type, value))
            return makeError(ErrorCode::kTruncated, where, ": data ends inside list ",
                             property.name);
          if (int(p) == indices) list.push_back(value);
        }
      }
      if (isVertex) {
        for (float c : xyz)
          if (!std::isfinite(c))
            return makeError(ErrorCode::kNonFinite, where, ": non-finite coordinate ", c);
        mesh.positions.insert(mesh.positions.end(), xyz, xyz + 3);
      } else if (isStrips) {
        VOXLINK_RETURN_IF_ERROR(addStrip(list, vertices, where, mesh));
      } else if (isFace) {
        VOXLINK_RETURN_IF_ERROR(addFace(list, vertices, where, mesh));
      }
      if (mesh.triangleCount() > maxTriangles)
        return makeError(ErrorCode::kTooLarge, path, ": more than the limit of ", maxTriangles,
                         " triangles");
    }
  }
  if (mesh.triangleCount() == 0) return makeError(ErrorCode::kCorrupt, path, ": no triangles");
  mesh.triangleMaterials.assign(mesh.triangleCount(), 0);
  mesh.materials.push_back(Material{"default"});
  return mesh;
}

}  // namespace voxlink::geometry
