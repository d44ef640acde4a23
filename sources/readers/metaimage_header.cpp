// SPDX-License-Identifier: BSD-3-Clause
#include "sources/readers/detail/metaimage_header.h"

#include <cmath>
#include <map>
#include <set>

#include "base/limits.h"
#include "sources/readers/detail/file_list.h"
#include "sources/readers/detail/text_header.h"

namespace voxlink::sources {
namespace {

constexpr size_t kMaxHeaderBytes = limits::kMaxTextHeaderBytes;

Result<ScalarType> metaType(std::string_view value, const std::string& file) {
  static const std::map<std::string, ScalarType, std::less<>> types = {
      {"MET_CHAR", ScalarType::kI8},   {"MET_UCHAR", ScalarType::kU8},
      {"MET_SHORT", ScalarType::kI16}, {"MET_USHORT", ScalarType::kU16},
      {"MET_INT", ScalarType::kI32},   {"MET_UINT", ScalarType::kU32},
      {"MET_LONG", ScalarType::kI32},  {"MET_ULONG", ScalarType::kU32},  // 4 bytes in MetaIO
      {"MET_FLOAT", ScalarType::kF32}, {"MET_DOUBLE", ScalarType::kF64}};
  const auto it = types.find(value);
  if (it != types.end()) return it->second;
  if (value.starts_with("MET_"))
    return makeError(ErrorCode::kUnsupported, file, ": header field 'ElementType': ", value,
                     " (MET_CHAR .. MET_DOUBLE scalars are supported)");
  return badField(file, "ElementType", "a MET_ type", value);
}

class MetaImageParser {
 public:
  explicit MetaImageParser(std::string path) : path_(std::move(path)) {}

  Result<MetaImageHeader> parse() {
    VOXLINK_ASSIGN_OR_RETURN(std::string text, readFilePrefix(path_, kMaxHeaderBytes));
    LineCursor lines(text);
    bool sawDataFile = false;
    while (auto line = lines.next(true)) {
      if (trim(*line).empty()) continue;
      const size_t eq = line->find('=');
      if (eq == std::string_view::npos)
        return makeError(ErrorCode::kCorrupt, path_, ": header line '", trim(*line).substr(0, 80),
                         "' is not 'Key = Value'");
      const std::string key(trim(line->substr(0, eq)));
      const std::string_view value = trim(line->substr(eq + 1));
      if (!seen_.insert(key).second)
        return makeError(ErrorCode::kCorrupt, path_, ": header field '", key, "' given twice");
      if (key == "ElementDataFile") {
        VOXLINK_RETURN_IF_ERROR(parseDataFile(value, lines));
        sawDataFile = true;
        break;
      }
      VOXLINK_RETURN_IF_ERROR(parseField(key, value));
    }
    if (!sawDataFile)
      return makeError(ErrorCode::kCorrupt, path_, ": header field 'ElementDataFile' missing");
    VOXLINK_RETURN_IF_ERROR(validate());
    return h_;
  }

 private:
  Status parseField(const std::string& key, std::string_view value) {
    if (key == "ObjectType") {
      if (value != "Image")
        return makeError(ErrorCode::kUnsupported, path_, ": header field 'ObjectType': ", value,
                         " (only Image)");
    } else if (key == "NDims") {
      VOXLINK_ASSIGN_OR_RETURN(int64_t n, parseInteger(value, path_, key));
      if (n < 1 || n > 16) return badField(path_, key, "an integer from 1 to 16", value);
      h_.ndims = static_cast<int>(n);
    } else if (key == "DimSize") {
      VOXLINK_ASSIGN_OR_RETURN(std::vector<int64_t> d, parseIntegers(value, path_, key));
      for (int64_t v : d) {
        if (v <= 0) return badField(path_, key, "positive integers", value);
        h_.dimSize.push_back(static_cast<uint64_t>(v));
      }
    } else if (key == "ElementType") {
      VOXLINK_ASSIGN_OR_RETURN(h_.type, metaType(value, path_));
    } else if (key == "ElementNumberOfChannels") {
      VOXLINK_ASSIGN_OR_RETURN(int64_t n, parseInteger(value, path_, key));
      if (n != 1)
        return makeError(ErrorCode::kUnsupported, path_,
                         ": header field 'ElementNumberOfChannels': ", n,
                         " (only scalar images, 1 channel)");
    } else if (key == "ElementSpacing") {
      VOXLINK_ASSIGN_OR_RETURN(h_.spacing, parseDoubles(value, path_, key));
      h_.spacingFromElementSize = false;
    } else if (key == "ElementSize") {
      if (!seen_.count("ElementSpacing")) {
        VOXLINK_ASSIGN_OR_RETURN(h_.spacing, parseDoubles(value, path_, key));
        h_.spacingFromElementSize = true;
      }
    } else if (key == "Offset" || key == "Origin" || key == "Position") {
      VOXLINK_ASSIGN_OR_RETURN(std::vector<double> v, parseDoubles(value, path_, key));
      if (v.size() < 3) return badField(path_, key, "3 numbers", value);
      for (int a = 0; a < 3; ++a)
        if (!std::isfinite(v[a])) return badField(path_, key, "3 finite numbers", value);
      h_.offset = Vec3{v[0], v[1], v[2]};
    } else if (key == "TransformMatrix" || key == "Rotation" || key == "Orientation") {
      VOXLINK_ASSIGN_OR_RETURN(std::vector<double> m, parseDoubles(value, path_, key));
      if (m.size() == 9)
        h_.axes = std::array<Vec3, 3>{{{m[0], m[1], m[2]}, {m[3], m[4], m[5]}, {m[6], m[7], m[8]}}};
      else if (m.size() != 16)
        return badField(path_, key, "9 numbers", value);
    } else if (key == "ElementByteOrderMSB" || key == "BinaryDataByteOrderMSB") {
      VOXLINK_ASSIGN_OR_RETURN(bool msb, parseBool(value, path_, key));
      h_.endian = msb ? Endian::kBig : Endian::kLittle;
    } else if (key == "BinaryData") {
      VOXLINK_ASSIGN_OR_RETURN(bool binary, parseBool(value, path_, key));
      if (!binary)
        return makeError(ErrorCode::kUnsupported, path_,
                         ": header field 'BinaryData': False (ASCII data is not supported)");
    } else if (key == "CompressedData") {
      VOXLINK_ASSIGN_OR_RETURN(h_.compressed, parseBool(value, path_, key));
    } else if (key == "CompressedDataSize") {
      VOXLINK_ASSIGN_OR_RETURN(int64_t n, parseInteger(value, path_, key));
      if (n <= 0) return badField(path_, key, "a positive byte count", value);
      h_.compressedSize = static_cast<uint64_t>(n);
    } else if (key == "HeaderSize") {
      VOXLINK_ASSIGN_OR_RETURN(h_.headerSize, parseInteger(value, path_, key));
      if (h_.headerSize < -1) return badField(path_, key, "-1 or a byte count >= 0", value);
    }
    // Other keys (AnatomicalOrientation, CenterOfRotation, ElementMin, Comment, ...) do not
    // change the voxels.
    return Status::ok();
  }

  Status parseDataFile(std::string_view value, LineCursor& lines) {
    const std::vector<std::string> words = splitWords(value);
    if (words.empty())
      return badField(path_, "ElementDataFile", "LOCAL, a file name or LIST", value);
    if (words[0] == "LOCAL") {
      h_.local = true;
      h_.localOffset = lines.offset();
      return Status::ok();
    }
    if (words[0] == "LIST") {
      while (auto line = lines.next(true))
        for (const std::string& name : splitWords(*line))
          h_.dataFiles.push_back(besideHeader(path_, name));
      if (h_.dataFiles.empty())
        return badField(path_, "ElementDataFile", "file names after LIST", "");
      return Status::ok();
    }
    if (words[0].find('%') != std::string::npos && words.size() == 4) {
      return appendNumberedFiles(words, path_, "ElementDataFile", h_.dataFiles);
    }
    h_.dataFiles.push_back(besideHeader(path_, std::string(value)));
    return Status::ok();
  }

  Status validate() {
    if (h_.ndims == 0)
      return makeError(ErrorCode::kCorrupt, path_, ": header field 'NDims' missing");
    if (!seen_.count("DimSize"))
      return makeError(ErrorCode::kCorrupt, path_, ": header field 'DimSize' missing");
    if (!seen_.count("ElementType"))
      return makeError(ErrorCode::kCorrupt, path_, ": header field 'ElementType' missing");
    if (h_.dimSize.size() != static_cast<size_t>(h_.ndims))
      return makeError(ErrorCode::kCorrupt, path_, ": header field 'DimSize': ", h_.dimSize.size(),
                       " sizes for NDims ", h_.ndims);
    const bool fourWithStub = h_.ndims == 4 && h_.dimSize[3] == 1;
    if (h_.ndims != 3 && !fourWithStub)
      return makeError(ErrorCode::kUnsupported, path_, ": header field 'NDims': ", h_.ndims,
                       " (a volume needs 3, or 4 with a last size of 1)");
    if (!h_.spacing.empty() && h_.spacing.size() < 3)
      return makeError(ErrorCode::kCorrupt, path_, ": header field '",
                       h_.spacingFromElementSize ? "ElementSize" : "ElementSpacing",
                       "': ", h_.spacing.size(), " values for NDims ", h_.ndims);
    if (h_.headerSize == -1 && h_.compressed)
      return makeError(ErrorCode::kUnsupported, path_,
                       ": header field 'HeaderSize': -1 with compressed data");
    return Status::ok();
  }

  std::string path_;
  MetaImageHeader h_;
  std::set<std::string> seen_;
};

}  // namespace

Result<MetaImageHeader> parseMetaImageHeader(const std::string& path) {
  return MetaImageParser(path).parse();
}

}  // namespace voxlink::sources
