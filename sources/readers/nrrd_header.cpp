// SPDX-License-Identifier: BSD-3-Clause
#include "sources/readers/detail/nrrd_header.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <map>
#include <set>

#include "base/limits.h"
#include "sources/readers/detail/file_list.h"
#include "sources/readers/detail/text_header.h"

namespace voxlink::sources {
namespace {

constexpr size_t kMaxHeaderBytes = limits::kMaxTextHeaderBytes;

// Every field spelling teem accepts, mapped to one canonical name.
const std::map<std::string, std::string>& fieldNames() {
  static const std::map<std::string, std::string> names = {
      {"content", "content"},
      {"number", "number"},
      {"type", "type"},
      {"block size", "block size"},
      {"blocksize", "block size"},
      {"dimension", "dimension"},
      {"space", "space"},
      {"space dimension", "space dimension"},
      {"spacedimension", "space dimension"},
      {"sizes", "sizes"},
      {"spacings", "spacings"},
      {"thicknesses", "thicknesses"},
      {"axis mins", "axis mins"},
      {"axismins", "axis mins"},
      {"axis maxs", "axis maxs"},
      {"axismaxs", "axis maxs"},
      {"centers", "centers"},
      {"centerings", "centers"},
      {"kinds", "kinds"},
      {"labels", "labels"},
      {"units", "units"},
      {"min", "min"},
      {"max", "max"},
      {"old min", "old min"},
      {"oldmin", "old min"},
      {"old max", "old max"},
      {"oldmax", "old max"},
      {"endian", "endian"},
      {"encoding", "encoding"},
      {"line skip", "line skip"},
      {"lineskip", "line skip"},
      {"byte skip", "byte skip"},
      {"byteskip", "byte skip"},
      {"data file", "data file"},
      {"datafile", "data file"},
      {"space units", "space units"},
      {"spaceunits", "space units"},
      {"sample units", "sample units"},
      {"sampleunits", "sample units"},
      {"space origin", "space origin"},
      {"spaceorigin", "space origin"},
      {"space directions", "space directions"},
      {"spacedirections", "space directions"},
      {"measurement frame", "measurement frame"},
      {"measurementframe", "measurement frame"},
  };
  return names;
}

// Fields that describe things a scalar volume does not use.
const std::set<std::string>& ignorableFields() {
  static const std::set<std::string> names = {
      "content",          "number",    "block size",  "thicknesses",
      "axis mins",        "axis maxs", "centers",     "kinds",
      "labels",           "units",     "min",         "max",
      "old min",          "old max",   "space units", "sample units",
      "measurement frame"};
  return names;
}

// Spaces of dimension 3 (teem's nrrdSpace names and abbreviations).
bool isThreeDimensionalSpace(const std::string& lower) {
  static const std::set<std::string> spaces = {"right-anterior-superior",
                                               "ras",
                                               "left-anterior-superior",
                                               "las",
                                               "left-posterior-superior",
                                               "lps",
                                               "scanner-xyz",
                                               "3d-right-handed",
                                               "3d-left-handed"};
  return spaces.count(lower) > 0;
}

// "(1.5,0,0)" -> vector; "none" -> nullopt.
Result<std::optional<Vec3>> parseVector(std::string_view text, size_t components,
                                        const std::string& file, std::string_view field) {
  text = trim(text);
  if (equalsIgnoreCase(text, "none")) return std::optional<Vec3>();
  if (text.size() < 2 || text.front() != '(' || text.back() != ')')
    return badField(file, field, "a vector like (1,0,0)", text);
  std::string inner(text.substr(1, text.size() - 2));
  std::replace(inner.begin(), inner.end(), ',', ' ');
  VOXLINK_ASSIGN_OR_RETURN(std::vector<double> v, parseDoubles(inner, file, field, components));
  if (components != 3)
    return makeError(ErrorCode::kUnsupported, file, ": header field '", field, "': ", components,
                     "-D space; only 3-D spaces are supported");
  return std::optional<Vec3>(Vec3{v[0], v[1], v[2]});
}

// Splits "(a,b,c) (d,e,f) none" into per-axis words (vectors may contain spaces).
std::vector<std::string> splitVectors(std::string_view text) {
  std::vector<std::string> out;
  std::string current;
  int depth = 0;
  for (char c : text) {
    if (c == '(') ++depth;
    if (c == ')') --depth;
    if (std::isspace(static_cast<unsigned char>(c)) && depth == 0) {
      if (!current.empty()) out.push_back(current);
      current.clear();
    } else {
      current += c;
    }
  }
  if (!current.empty()) out.push_back(current);
  return out;
}

class NrrdParser {
 public:
  explicit NrrdParser(std::string path) : path_(std::move(path)) {}

  Result<NrrdHeader> parse() {
    VOXLINK_ASSIGN_OR_RETURN(std::string text, readFilePrefix(path_, kMaxHeaderBytes));
    LineCursor lines(text);
    const auto magic = lines.next(false);
    if (!magic || magic->size() != 8 || !magic->starts_with("NRRD000") ||
        !std::isdigit(static_cast<unsigned char>((*magic)[7])))
      return makeError(ErrorCode::kCorrupt, path_,
                       ": not a NRRD file (first line is not NRRD000X)");
    h_.version = (*magic)[7] - '0';
    if (h_.version < 1 || h_.version > 5)
      return makeError(ErrorCode::kUnsupported, path_, ": NRRD version ", *magic,
                       " (1 to 5 are known)");

    bool blankLine = false;
    while (auto line = lines.next(false)) {
      if (line->empty()) {
        blankLine = true;
        break;
      }
      if (line->front() == '#') continue;
      if (listingFiles_) {
        h_.dataFiles.push_back(besideHeader(path_, std::string(trim(*line))));
        continue;
      }
      VOXLINK_RETURN_IF_ERROR(parseLine(*line));
    }
    if (!blankLine && !lines.atEnd()) {
      // A last header line without newline, or a header bigger than we read.
      if (text.size() >= kMaxHeaderBytes)
        return makeError(ErrorCode::kCorrupt, path_,
                         ": no blank line ending the header in the first ", kMaxHeaderBytes,
                         " bytes");
      if (auto last = lines.next(true); last && !last->empty() && last->front() != '#') {
        if (listingFiles_)
          h_.dataFiles.push_back(besideHeader(path_, std::string(trim(*last))));
        else
          VOXLINK_RETURN_IF_ERROR(parseLine(*last));
      }
    }
    if (!seen_.count("data file")) {
      if (!blankLine)
        return makeError(ErrorCode::kCorrupt, path_,
                         ": header field 'data file' missing and no "
                         "blank line before attached data");
      h_.attached = true;
      h_.dataOffset = lines.offset();
    }
    VOXLINK_RETURN_IF_ERROR(validate());
    return h_;
  }

 private:
  Status parseLine(std::string_view line) {
    const size_t colon = line.find(':');
    if (colon == std::string_view::npos)
      return makeError(ErrorCode::kCorrupt, path_, ": header line '", line,
                       "' is not 'field: value'");
    if (colon + 1 < line.size() && line[colon + 1] == '=') return Status::ok();  // key:=value
    const std::string name = toLower(trim(line.substr(0, colon)));
    const std::string_view value = trim(line.substr(colon + 1));
    const auto known = fieldNames().find(name);
    if (known == fieldNames().end())
      return makeError(ErrorCode::kUnsupported, path_, ": unknown header field '", name, "'");
    const std::string& field = known->second;
    if (!seen_.insert(field).second)
      return makeError(ErrorCode::kCorrupt, path_, ": header field '", field, "' given twice");
    if (ignorableFields().count(field)) {
      h_.ignoredFields.push_back(field);
      return Status::ok();
    }
    return parseField(field, value);
  }

  Status parseField(const std::string& field, std::string_view value) {
    if (field == "dimension") {
      VOXLINK_ASSIGN_OR_RETURN(int64_t d, parseInteger(value, path_, field));
      if (d < 1 || d > 16) return badField(path_, field, "an integer from 1 to 16", value);
      h_.dimension = static_cast<int>(d);
    } else if (field == "type") {
      const std::string lower = toLower(value);
      if (lower == "block")
        return makeError(ErrorCode::kUnsupported, path_,
                         ": header field 'type': block (opaque records) is not a scalar type");
      const auto t = nrrdTypeFromName(lower);
      if (!t) {
        if (lower.find("long") != std::string::npos || lower.find("64") != std::string::npos)
          return makeError(ErrorCode::kUnsupported, path_, ": header field 'type': ", value,
                           " (64-bit integers are not supported)");
        return badField(path_, field, "a NRRD type name", value);
      }
      h_.type = *t;
    } else if (field == "sizes") {
      sizesText_ = std::string(value);
      VOXLINK_ASSIGN_OR_RETURN(std::vector<int64_t> s, parseIntegers(value, path_, field));
      for (int64_t v : s) {
        if (v <= 0) return badField(path_, field, "positive integers", value);
        h_.sizes.push_back(static_cast<uint64_t>(v));
      }
    } else if (field == "spacings") {
      VOXLINK_ASSIGN_OR_RETURN(h_.spacings, parseDoubles(value, path_, field));
    } else if (field == "space") {
      if (!isThreeDimensionalSpace(toLower(value)))
        return makeError(ErrorCode::kUnsupported, path_, ": header field 'space': ", value,
                         " (only 3-D spaces are supported)");
      spaceDimension_ = 3;
    } else if (field == "space dimension") {
      VOXLINK_ASSIGN_OR_RETURN(int64_t d, parseInteger(value, path_, field));
      if (d != 3)
        return makeError(ErrorCode::kUnsupported, path_, ": header field 'space dimension': ", d,
                         " (only 3 is supported)");
      spaceDimension_ = 3;
    } else if (field == "space directions") {
      for (const std::string& word : splitVectors(value)) {
        VOXLINK_ASSIGN_OR_RETURN(auto v, parseVector(word, vectorComponents(word), path_, field));
        h_.directions.push_back(v);
      }
    } else if (field == "space origin") {
      VOXLINK_ASSIGN_OR_RETURN(auto v, parseVector(value, vectorComponents(value), path_, field));
      if (!v) return badField(path_, field, "a vector like (0,0,0)", value);
      for (double c : *v)
        if (!std::isfinite(c)) return badField(path_, field, "finite coordinates", value);
      h_.origin = *v;
    } else if (field == "encoding") {
      const std::string lower = toLower(value);
      if (lower == "raw") {
        h_.encoding = PieceEncoding::kRaw;
      } else if (lower == "gzip" || lower == "gz") {
        h_.encoding = PieceEncoding::kDeflate;
      } else if (lower == "bzip2" || lower == "bz2" || lower == "txt" || lower == "text" ||
                 lower == "ascii" || lower == "hex" || lower == "zrl") {
        return makeError(ErrorCode::kUnsupported, path_, ": header field 'encoding': ", value,
                         " (raw and gzip are supported)");
      } else {
        return badField(path_, field, "a NRRD encoding", value);
      }
    } else if (field == "endian") {
      const std::string lower = toLower(value);
      if (lower == "little")
        h_.endian = Endian::kLittle;
      else if (lower == "big")
        h_.endian = Endian::kBig;
      else
        return badField(path_, field, "little or big", value);
    } else if (field == "line skip") {
      VOXLINK_ASSIGN_OR_RETURN(int64_t n, parseInteger(value, path_, field));
      if (n < 0) return badField(path_, field, "a count of lines >= 0", value);
      h_.lineSkip = static_cast<uint64_t>(n);
    } else if (field == "byte skip") {
      VOXLINK_ASSIGN_OR_RETURN(h_.byteSkip, parseInteger(value, path_, field));
      if (h_.byteSkip < -1) return badField(path_, field, "-1 or a count of bytes >= 0", value);
    } else if (field == "data file") {
      return parseDataFile(value);
    }
    return Status::ok();
  }

  size_t vectorComponents(std::string_view word) const {
    return static_cast<size_t>(std::count(word.begin(), word.end(), ',') + 1);
  }

  Status parseDataFile(std::string_view value) {
    const std::vector<std::string> words = splitWords(value);
    if (words.empty()) return badField(path_, "data file", "a file name", value);
    if (words[0] == "LIST") {
      if (words.size() > 2) return badField(path_, "data file", "'LIST [<subdim>]'", value);
      if (words.size() == 2) VOXLINK_RETURN_IF_ERROR(parseSubdim(words[1]));
      listingFiles_ = true;
      return Status::ok();
    }
    if (words.size() >= 4 && words[0].find('%') != std::string::npos) {
      std::vector<std::string> list(words.begin(), words.begin() + 4);
      if (words.size() == 5)
        VOXLINK_RETURN_IF_ERROR(parseSubdim(words[4]));
      else if (words.size() > 5)
        return badField(path_, "data file", "'<format> <min> <max> <step> [<subdim>]'", value);
      return appendNumberedFiles(list, path_, "data file", h_.dataFiles);
    }
    // A single file; its name may contain spaces.
    h_.dataFiles.push_back(besideHeader(path_, std::string(value)));
    return Status::ok();
  }

  Status parseSubdim(const std::string& word) {
    VOXLINK_ASSIGN_OR_RETURN(int64_t s, parseInteger(word, path_, "data file"));
    if (s < 1) return badField(path_, "data file", "a sub-dimension >= 1", word);
    h_.dataFileSubdim = static_cast<int>(s);
    return Status::ok();
  }

  Status validate() {
    for (const char* required : {"dimension", "type", "sizes", "encoding"})
      if (!seen_.count(required))
        return makeError(ErrorCode::kCorrupt, path_, ": header field '", required, "' missing");
    const int d = h_.dimension;
    if (h_.sizes.size() != static_cast<size_t>(d))
      return badField(path_, "sizes", cat(d, " positive integers (dimension ", d, ")"), sizesText_);
    const bool fourWithStub = d == 4 && h_.sizes[0] == 1;
    if (d != 3 && !fourWithStub)
      return makeError(
          ErrorCode::kUnsupported, path_, ": header field 'dimension': ", d,
          d == 4 ? " with a first axis of size " + std::to_string(h_.sizes[0]) : std::string(),
          " (a volume needs dimension 3, or 4 with a first axis of size 1)");
    if (!h_.spacings.empty() && h_.spacings.size() != static_cast<size_t>(d))
      return makeError(ErrorCode::kCorrupt, path_,
                       ": header field 'spacings': ", h_.spacings.size(), " values for dimension ",
                       d);
    if (!h_.directions.empty()) {
      if (!h_.spacings.empty())
        return makeError(ErrorCode::kCorrupt, path_,
                         ": header fields 'spacings' and 'space directions' both given");
      if (h_.directions.size() != static_cast<size_t>(d))
        return makeError(ErrorCode::kCorrupt, path_,
                         ": header field 'space directions': ", h_.directions.size(),
                         " vectors for dimension ", d);
      if (spaceDimension_ == 0)
        return makeError(ErrorCode::kCorrupt, path_,
                         ": header field 'space directions' without 'space' or 'space dimension'");
    }
    if (h_.origin && spaceDimension_ == 0)
      return makeError(ErrorCode::kCorrupt, path_,
                       ": header field 'space origin' without 'space' or 'space dimension'");
    if (scalarSize(h_.type) > 1 && !h_.endian)
      return makeError(ErrorCode::kCorrupt, path_, ": header field 'endian' missing; type ",
                       scalarName(h_.type), " needs it");
    if (h_.byteSkip == -1 && h_.encoding != PieceEncoding::kRaw)
      return makeError(ErrorCode::kUnsupported, path_,
                       ": header field 'byte skip': -1 is only defined for raw encoding");
    if (seen_.count("data file") && h_.dataFiles.empty())
      return makeError(ErrorCode::kCorrupt, path_,
                       ": header field 'data file': LIST names no files");
    return Status::ok();
  }

  std::string path_;
  NrrdHeader h_;
  std::set<std::string> seen_;
  std::string sizesText_;
  int spaceDimension_ = 0;
  bool listingFiles_ = false;
};

}  // namespace

std::optional<ScalarType> nrrdTypeFromName(const std::string& name) {
  static const std::map<std::string, ScalarType> types = {
      {"signed char", ScalarType::kI8},
      {"int8", ScalarType::kI8},
      {"int8_t", ScalarType::kI8},
      {"uchar", ScalarType::kU8},
      {"unsigned char", ScalarType::kU8},
      {"uint8", ScalarType::kU8},
      {"uint8_t", ScalarType::kU8},
      {"short", ScalarType::kI16},
      {"short int", ScalarType::kI16},
      {"signed short", ScalarType::kI16},
      {"signed short int", ScalarType::kI16},
      {"int16", ScalarType::kI16},
      {"int16_t", ScalarType::kI16},
      {"ushort", ScalarType::kU16},
      {"unsigned short", ScalarType::kU16},
      {"unsigned short int", ScalarType::kU16},
      {"uint16", ScalarType::kU16},
      {"uint16_t", ScalarType::kU16},
      {"int", ScalarType::kI32},
      {"signed int", ScalarType::kI32},
      {"int32", ScalarType::kI32},
      {"int32_t", ScalarType::kI32},
      {"uint", ScalarType::kU32},
      {"unsigned int", ScalarType::kU32},
      {"uint32", ScalarType::kU32},
      {"uint32_t", ScalarType::kU32},
      {"float", ScalarType::kF32},
      {"double", ScalarType::kF64},
  };
  const auto it = types.find(toLower(name));
  if (it == types.end()) return std::nullopt;
  return it->second;
}

Result<NrrdHeader> parseNrrdHeader(const std::string& path) { return NrrdParser(path).parse(); }

}  // namespace voxlink::sources
