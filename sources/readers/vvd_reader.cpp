// SPDX-License-Identifier: BSD-3-Clause
#include "sources/readers/vvd_reader.h"

#include <map>

#include "base/limits.h"
#include "sources/readers/detail/axes.h"
#include "sources/readers/detail/data_pieces.h"
#include "sources/readers/detail/file_list.h"
#include "sources/readers/detail/text_header.h"
#include "sources/readers/detail/xml_tags.h"
#include "sources/readers/reader_common.h"

namespace voxlink::sources {
namespace {

constexpr size_t kMaxHeaderBytes = limits::kMaxVvdHeaderBytes;

Result<ScalarType> voreenFormat(const std::string& format, const std::string& file) {
  static const std::map<std::string, ScalarType> formats = {
      {"uint8", ScalarType::kU8},  {"int8", ScalarType::kI8},    {"uint16", ScalarType::kU16},
      {"int16", ScalarType::kI16}, {"uint32", ScalarType::kU32}, {"int32", ScalarType::kI32},
      {"float", ScalarType::kF32}, {"double", ScalarType::kF64}};
  const auto it = formats.find(format);
  if (it != formats.end()) return it->second;
  return makeError(ErrorCode::kUnsupported, file, ": RawData attribute 'format': ", format,
                   " (scalar uint8 .. double are supported)");
}

Result<uint64_t> dimAttribute(const XmlTag& tag, const char* key, const std::string& file) {
  const std::string* v = tag.attribute(key);
  const std::string field = cat("RawData ", key);
  if (!v) return makeError(ErrorCode::kCorrupt, file, ": header field '", field, "' missing");
  VOXLINK_ASSIGN_OR_RETURN(int64_t n, parseInteger(*v, file, field));
  if (n <= 0) return badField(file, field, "a positive size", *v);
  return static_cast<uint64_t>(n);
}

// The <value x= y= z=/> of <MetaItem name="NAME"> among elements [from, until), if present.
Result<std::optional<Vec3>> metaVector(const XmlHeader& xml, const char* name, size_t from,
                                       size_t until, const std::string& file) {
  for (size_t at = from;; ++at) {
    at = xml.find("MetaItem", at, until);
    if (at == XmlHeader::kNone) return std::optional<Vec3>();
    const std::string* n = xml[at].attribute("name");
    if (!n || *n != name) continue;
    const size_t valueAt = xml.find("value", at + 1, until);
    const std::string field = cat("MetaItem ", name);
    if (valueAt == XmlHeader::kNone)
      return makeError(ErrorCode::kCorrupt, file, ": header field '", field, "' has no <value>");
    const XmlTag* value = &xml[valueAt];
    Vec3 v{};
    for (int a = 0; a < 3; ++a) {
      const std::string* text = value->attribute(std::string(1, "xyz"[a]));
      if (!text)
        return makeError(ErrorCode::kCorrupt, file, ": header field '", field, "': value has no ",
                         "xyz"[a]);
      VOXLINK_ASSIGN_OR_RETURN(std::vector<double> d, parseDoubles(*text, file, field, 1));
      v[a] = d[0];
    }
    return std::optional<Vec3>(v);
  }
}

}  // namespace

Result<std::unique_ptr<VolumeSource>> openVvd(const std::string& path, const OpenOptions& options) {
  VOXLINK_ASSIGN_OR_RETURN(std::string xml, readFilePrefix(path, kMaxHeaderBytes));
  if (xml.find("<VoreenData") == std::string::npos)
    return makeError(ErrorCode::kCorrupt, path,
                     ": not a Voreen .vvd file (no <VoreenData> element)");
  // The header may be cut at kMaxHeaderBytes: what it holds so far counts.
  VOXLINK_ASSIGN_OR_RETURN(const XmlHeader header, XmlHeader::parse(xml, path, {}, true));
  const size_t volume = header.find("Volume");
  if (volume == XmlHeader::kNone)
    return makeError(ErrorCode::kCorrupt, path, ": no <Volume> element");
  // A header read whole must close its volume: a cut file would otherwise pass. (With nothing
  // after it, the volume or an element around it is open.)
  if (header.endedOpen() && !header[volume].followed && xml.size() < kMaxHeaderBytes)
    return makeError(ErrorCode::kTruncated, path,
                     ": <Volume> element is not closed (truncated header?)");
  const size_t volumeEnd = header[volume].subtreeEnd;
  const size_t rawAt = header.find("RawData", volume + 1, volumeEnd);
  if (rawAt == XmlHeader::kNone)
    return makeError(ErrorCode::kCorrupt, path,
                     ": header field 'RawData' missing in the first <Volume>");
  const XmlTag* raw = &header[rawAt];

  const std::string* filename = raw->attribute("filename");
  const std::string* format = raw->attribute("format");
  if (!filename || filename->empty())
    return makeError(ErrorCode::kCorrupt, path, ": header field 'RawData filename' missing");
  if (!format)
    return makeError(ErrorCode::kCorrupt, path, ": header field 'RawData format' missing");

  VolumeInfo info;
  info.path = path;
  info.format = "vvd";
  VOXLINK_ASSIGN_OR_RETURN(info.type, voreenFormat(*format, path));
  std::array<uint64_t, 3> dims{};
  VOXLINK_ASSIGN_OR_RETURN(dims[0], dimAttribute(*raw, "x", path));
  VOXLINK_ASSIGN_OR_RETURN(dims[1], dimAttribute(*raw, "y", path));
  VOXLINK_ASSIGN_OR_RETURN(dims[2], dimAttribute(*raw, "z", path));
  VOXLINK_RETURN_IF_ERROR(checkDims(dims, path, "RawData x y z"));
  for (int a = 0; a < 3; ++a) info.dims[a] = static_cast<uint32_t>(dims[a]);

  VOXLINK_ASSIGN_OR_RETURN(auto spacing,
                           metaVector(header, "Spacing", volume + 1, volumeEnd, path));
  VOXLINK_ASSIGN_OR_RETURN(auto offset, metaVector(header, "Offset", volume + 1, volumeEnd, path));
  if (spacing) {
    info.spacing = *spacing;
    VOXLINK_RETURN_IF_ERROR(checkSpacing(info.spacing, path, "MetaItem Spacing"));
  } else {
    info.notes.push_back("no Spacing meta item: spacing 1 1 1");
  }
  if (offset) {
    info.origin = *offset;
    VOXLINK_RETURN_IF_ERROR(checkOrigin(info.origin, path, "MetaItem Offset"));
  }
  if (xml.find("name=\"RealWorldMapping\"") != std::string::npos)
    info.notes.push_back("RealWorldMapping meta item not applied: values are the raw file's");
  if (xml.find("name=\"Transformation\"") != std::string::npos)
    info.notes.push_back("Transformation meta item ignored: voxels stay in index order");
  if (header.find("Volume", volumeEnd) != XmlHeader::kNone)
    info.notes.push_back("the file describes more than one volume; the first is read");
  VOXLINK_RETURN_IF_ERROR(applyOpenOptions(info, options));

  PieceLayout layout;
  layout.label = cat(path, ": RawData filename");
  layout.endian = Endian::kLittle;  // Voreen writes host (x86) order
  DataPiece piece;
  piece.path = besideHeader(path, *filename);
  piece.slices = info.dims[2];
  layout.pieces.push_back(piece);
  return openDataPieces(std::move(info), std::move(layout));
}

}  // namespace voxlink::sources
