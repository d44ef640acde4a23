// SPDX-License-Identifier: BSD-3-Clause
#include "sources/readers/vti_reader.h"

#include <zlib.h>

#include <algorithm>
#include <cstring>
#include <map>
#include <vector>

#include "base/checked_math.h"
#include "base/limits.h"
#include "sources/readers/detail/axes.h"
#include "sources/readers/detail/axis_reorder.h"
#include "sources/readers/detail/byte_order.h"
#include "sources/readers/detail/text_header.h"
#include "sources/readers/detail/xml_tags.h"
#include "sources/readers/reader_common.h"

namespace voxlink::sources {
namespace {

Result<std::vector<uint8_t>> decodeBase64(std::string_view text, const std::string& file) {
  static const auto table = [] {
    std::array<int8_t, 256> t{};
    t.fill(-1);
    const char* alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    for (int i = 0; i < 64; ++i) t[static_cast<uint8_t>(alphabet[i])] = static_cast<int8_t>(i);
    return t;
  }();
  std::vector<uint8_t> out;
  out.reserve(text.size() / 4 * 3);
  uint32_t bits = 0;
  int count = 0;
  for (char c : text) {
    if (c == '=' || std::isspace(static_cast<unsigned char>(c))) continue;
    const int v = table[static_cast<uint8_t>(c)];
    if (v < 0)
      return makeError(ErrorCode::kCorrupt, file, ": DataArray: invalid base64 character '", c,
                       "'");
    bits = bits << 6 | static_cast<uint32_t>(v);
    if (++count == 4) {
      out.push_back(static_cast<uint8_t>(bits >> 16));
      out.push_back(static_cast<uint8_t>(bits >> 8));
      out.push_back(static_cast<uint8_t>(bits));
      bits = 0;
      count = 0;
    }
  }
  if (count == 2) out.push_back(static_cast<uint8_t>(bits >> 4));
  if (count == 3) {
    out.push_back(static_cast<uint8_t>(bits >> 10));
    out.push_back(static_cast<uint8_t>(bits >> 2));
  }
  return out;
}

// Base64 characters that encode `bytes` bytes (VTK encodes header and data separately).
size_t base64Length(size_t bytes) { return (bytes + 2) / 3 * 4; }

struct Layout {
  std::string file;
  bool bigEndian = false;
  size_t headerWord = 4;  // header_type UInt32 or UInt64
  bool compressed = false;
  uint64_t expected = 0;  // decoded bytes the extent and type call for
};

uint64_t word(const uint8_t* p, const Layout& l) {
  uint64_t v = 0;
  for (size_t i = 0; i < l.headerWord; ++i) {
    const size_t at = l.bigEndian ? i : l.headerWord - 1 - i;
    v = v << 8 | p[at];
  }
  return v;
}

// Decodes [header][data] where `next(n)` yields the next n decoded bytes of the stream.
template <class Next>
Result<std::vector<uint8_t>> decodeArray(Next next, const Layout& l) {
  const auto bad = [&](auto... what) {
    return makeError(ErrorCode::kCorrupt, l.file, ": DataArray: ", what...);
  };
  if (!l.compressed) {
    VOXLINK_ASSIGN_OR_RETURN(std::vector<uint8_t> h, next(l.headerWord));
    const uint64_t size = word(h.data(), l);
    if (size != l.expected)
      return makeError(ErrorCode::kSizeMismatch, l.file, ": DataArray: ", size,
                       " bytes, the extent needs ", l.expected);
    return next(size);
  }
  VOXLINK_ASSIGN_OR_RETURN(std::vector<uint8_t> h, next(3 * l.headerWord));
  const uint64_t blocks = word(h.data(), l), blockSize = word(h.data() + l.headerWord, l);
  const uint64_t lastSize = word(h.data() + 2 * l.headerWord, l);
  // Every size below comes from the file: products and sums are checked, and the output is
  // allocated only once the compressed blocks are known to be present and large enough.
  // (VTK writes its default block size even for arrays smaller than one block.)
  if (blocks == 0 || blocks > limits::kMaxVtiBlocks || blockSize == 0 || lastSize > blockSize)
    return bad("bad compression header (", blocks, " blocks of ", blockSize, ", last ", lastSize,
               ")");
  const auto full = checkedMul(blocks - 1, blockSize);
  const auto total = full ? checkedAdd(*full, lastSize ? lastSize : blockSize) : std::nullopt;
  if (!total || *total != l.expected)
    return makeError(ErrorCode::kSizeMismatch, l.file, ": DataArray: ", blocks, " blocks of ",
                     blockSize, " bytes (last ", lastSize, ") do not make the ", l.expected,
                     " bytes the extent needs");
  VOXLINK_ASSIGN_OR_RETURN(std::vector<uint8_t> sizes, next(blocks * l.headerWord));
  uint64_t compressedTotal = 0;
  for (uint64_t b = 0; b < blocks; ++b) {
    const uint64_t csize = word(sizes.data() + b * l.headerWord, l);
    const uint64_t want = b + 1 == blocks && lastSize ? lastSize : blockSize;
    const auto sum = checkedAdd(compressedTotal, csize);
    const auto most = checkedMul(csize, limits::kMaxZlibRatio);
    if (!sum || *sum > limits::kMaxWholeFileBytes || !most || *most + 64 < want)
      return bad("compressed block ", b, " of ", csize, " bytes cannot hold ", want, " bytes");
    compressedTotal = *sum;
  }
  VOXLINK_ASSIGN_OR_RETURN(std::vector<uint8_t> packed, next(compressedTotal));
  std::vector<uint8_t> out;
  try {
    out.resize(*total);
  } catch (const std::bad_alloc&) {
    return makeError(ErrorCode::kTooLarge, l.file, ": DataArray: ", *total,
                     " bytes do not fit in memory");
  }
  uint64_t in = 0;
  for (uint64_t b = 0; b < blocks; ++b) {
    const uint64_t csize = word(sizes.data() + b * l.headerWord, l);
    uLongf outSize = static_cast<uLongf>(b + 1 == blocks && lastSize ? lastSize : blockSize);
    const uLongf want = outSize;
    // b * blockSize + want <= total and in + csize <= compressedTotal hold by the checks above.
    const int rc = uncompress(out.data() + b * blockSize, &outSize, packed.data() + in,
                              static_cast<uLong>(csize));
    if (rc != Z_OK || outSize != want)
      return bad("zlib block ", b, " is corrupt (zlib code ", rc, ")");
    in += csize;
  }
  return out;
}

class MemorySource final : public VolumeSource {
 public:
  MemorySource(VolumeInfo info, std::vector<uint8_t> data) : data_(std::move(data)) {
    info_ = std::move(info);
  }
  bool randomAccess() const override { return true; }
  Status read(uint32_t z0, uint32_t count, void* dst) override {
    VOXLINK_RETURN_IF_ERROR(checkSliceRange(z0, count));
    std::memcpy(dst, data_.data() + uint64_t{z0} * info_.sliceBytes(),
                uint64_t{count} * info_.sliceBytes());
    return Status::ok();
  }
  const void* map(uint32_t z0, uint32_t count) override {
    if (uint64_t{z0} + count > info_.dims[2]) return nullptr;
    return data_.data() + uint64_t{z0} * info_.sliceBytes();
  }

 private:
  std::vector<uint8_t> data_;
};

Result<ScalarType> vtkType(const std::string& name, const std::string& file) {
  static const std::map<std::string, ScalarType> types = {
      {"Int8", ScalarType::kI8},     {"UInt8", ScalarType::kU8},   {"Int16", ScalarType::kI16},
      {"UInt16", ScalarType::kU16},  {"Int32", ScalarType::kI32},  {"UInt32", ScalarType::kU32},
      {"Float32", ScalarType::kF32}, {"Float64", ScalarType::kF64}};
  const auto it = types.find(name);
  if (it == types.end())
    return makeError(ErrorCode::kUnsupported, file, ": DataArray attribute 'type': ", name,
                     " (Int8 .. Float64 are supported)");
  return it->second;
}

const std::string& requireAttribute(const XmlTag& tag, const std::string& key, Status& status,
                                    const std::string& file) {
  static const std::string empty;
  const std::string* v = tag.attribute(key);
  if (!v) {
    if (status.isOk())
      status =
          makeError(ErrorCode::kCorrupt, file, ": <", tag.name, "> attribute '", key, "' missing");
    return empty;
  }
  return *v;
}

std::string arrayName(const XmlTag& array) {
  const std::string* n = array.attribute("Name");
  return n ? *n : std::string();
}

std::string componentCount(const XmlTag& array) {
  const std::string* n = array.attribute("NumberOfComponents");
  return n ? std::string(trim(*n)) : "1";
}

// The point-data array to read: the one `variable` (--variable) names; without it the scalar
// array the `Scalars` attribute names, else the first scalar (one-component) array, with a note
// listing them all. Vector arrays are skipped, not refused, so a scalar array after one is read.
Result<XmlTag> pickArray(const XmlHeader& xml, size_t pointData, const std::string& variable,
                         const std::string& path, std::vector<std::string>& notes) {
  std::vector<XmlTag> arrays;
  for (size_t at = pointData + 1;; ++at) {
    at = xml.find("DataArray", at, xml[pointData].subtreeEnd);
    if (at == XmlHeader::kNone) break;
    arrays.push_back(xml[at]);
  }
  if (arrays.empty())
    return makeError(ErrorCode::kUnsupported, path, ": no <DataArray> in <PointData>");
  const auto isScalar = [](const XmlTag& a) { return componentCount(a) == "1"; };
  std::string all, scalars;  // for notes and errors: 'a', 'v' (3 components)
  for (const XmlTag& a : arrays) {
    const std::string shown = cat("'", arrayName(a), "'");
    all += cat(all.empty() ? "" : ", ", shown,
               isScalar(a) ? "" : cat(" (", componentCount(a), " components)"));
    if (isScalar(a)) scalars += cat(scalars.empty() ? "" : ", ", shown);
  }
  if (scalars.empty()) scalars = "none";
  if (!variable.empty()) {
    const auto it = std::find_if(arrays.begin(), arrays.end(),
                                 [&](const XmlTag& a) { return arrayName(a) == variable; });
    if (it == arrays.end())
      return makeError(ErrorCode::kInvalidArgument, path, ": --variable '", variable,
                       "': no point data array of that name (scalar arrays: ", scalars, ")");
    if (!isScalar(*it))
      return makeError(ErrorCode::kUnsupported, path, ": DataArray '", variable,
                       "' attribute 'NumberOfComponents': ", componentCount(*it),
                       " (only scalars; scalar arrays: ", scalars, ")");
    return *it;
  }
  const std::string* wanted = xml[pointData].attribute("Scalars");
  auto chosen = std::find_if(arrays.begin(), arrays.end(), [&](const XmlTag& a) {
    return wanted && arrayName(a) == *wanted && isScalar(a);
  });
  if (chosen == arrays.end()) chosen = std::find_if(arrays.begin(), arrays.end(), isScalar);
  if (chosen == arrays.end())
    return makeError(ErrorCode::kUnsupported, path,
                     ": DataArray attribute 'NumberOfComponents': no scalar point data array "
                     "(arrays: ",
                     all, ")");
  if (arrays.size() > 1)
    notes.push_back(cat("point data arrays ", all, ": reading '", arrayName(*chosen),
                        "' (--variable NAME picks another)"));
  else if (chosen->attribute("Name"))
    notes.push_back(cat("point data array '", arrayName(*chosen), "'"));
  return *chosen;
}

// The XML elements. Appended data may be raw bytes (not XML) and large: the parser reads the
// first MiB, and the whole file only when the header (or inline data) goes on past it, so a
// large appended array is not copied into the parser.
Result<XmlHeader> parseHeader(std::string_view xml, const std::string& path) {
  constexpr size_t kFirstBytes = size_t{1} << 20;
  if (xml.size() > kFirstBytes) {
    VOXLINK_ASSIGN_OR_RETURN(XmlHeader first,
                             XmlHeader::parse(xml.substr(0, kFirstBytes), path, "AppendedData",
                                              /*cutShort=*/true));
    if (!first.endedOpen()) return first;
  }
  return XmlHeader::parse(xml, path, "AppendedData");
}

}  // namespace

Result<std::unique_ptr<VolumeSource>> openVti(const std::string& path, const OpenOptions& options) {
  VOXLINK_ASSIGN_OR_RETURN(std::string xml, readFilePrefix(path, limits::kMaxWholeFileBytes));
  VOXLINK_ASSIGN_OR_RETURN(const XmlHeader header, parseHeader(xml, path));
  const size_t rootAt = header.find("VTKFile");
  const XmlTag* root = rootAt == XmlHeader::kNone ? nullptr : &header[rootAt];
  if (!root || !root->attribute("type") || *root->attribute("type") != "ImageData")
    return makeError(ErrorCode::kCorrupt, path,
                     ": not a VTK XML ImageData file (<VTKFile type=\"ImageData\">)");
  Layout layout;
  layout.file = path;
  layout.bigEndian = root->attribute("byte_order") && *root->attribute("byte_order") == "BigEndian";
  if (const std::string* h = root->attribute("header_type")) {
    if (*h == "UInt64")
      layout.headerWord = 8;
    else if (*h != "UInt32")
      return makeError(ErrorCode::kUnsupported, path, ": VTKFile attribute 'header_type': ", *h);
  }
  if (const std::string* c = root->attribute("compressor"); c && !c->empty()) {
    if (*c != "vtkZLibDataCompressor")
      return makeError(ErrorCode::kUnsupported, path, ": VTKFile attribute 'compressor': ", *c,
                       " (only vtkZLibDataCompressor)");
    layout.compressed = true;
  }

  const size_t imageAt = header.find("ImageData", rootAt + 1);
  if (imageAt == XmlHeader::kNone)
    return makeError(ErrorCode::kCorrupt, path, ": no <ImageData> element");
  const XmlTag* image = &header[imageAt];
  Status status;
  const std::string extentText = requireAttribute(*image, "WholeExtent", status, path);
  VOXLINK_RETURN_IF_ERROR(status);
  VOXLINK_ASSIGN_OR_RETURN(std::vector<int64_t> extent,
                           parseIntegers(extentText, path, "WholeExtent", 6));
  std::array<uint64_t, 3> dims{};
  for (int a = 0; a < 3; ++a) {
    if (extent[2 * a + 1] < extent[2 * a])
      return badField(path, "WholeExtent", "min <= max on each axis", extentText);
    dims[a] = static_cast<uint64_t>(extent[2 * a + 1] - extent[2 * a] + 1);
  }
  VOXLINK_RETURN_IF_ERROR(checkDims(dims, path, "WholeExtent"));

  VolumeInfo info;
  info.path = path;
  info.format = "vti";
  for (int a = 0; a < 3; ++a) info.dims[a] = static_cast<uint32_t>(dims[a]);
  Vec3 origin{0, 0, 0};
  if (const std::string* s = image->attribute("Spacing")) {
    VOXLINK_ASSIGN_OR_RETURN(std::vector<double> v, parseDoubles(*s, path, "Spacing", 3));
    info.spacing = {v[0], v[1], v[2]};
    VOXLINK_RETURN_IF_ERROR(checkSpacing(info.spacing, path, "Spacing"));
  }
  if (const std::string* o = image->attribute("Origin")) {
    VOXLINK_ASSIGN_OR_RETURN(std::vector<double> v, parseDoubles(*o, path, "Origin", 3));
    origin = {v[0], v[1], v[2]};
    VOXLINK_RETURN_IF_ERROR(checkOrigin(origin, path, "Origin"));
  }
  std::array<Vec3, 3> axes{Vec3{1, 0, 0}, Vec3{0, 1, 0}, Vec3{0, 0, 1}};
  // A Direction along the coordinate axes but reversed or permuted: the voxels are reordered
  // below so that the grid runs along +x, +y, +z and every voxel keeps its world position.
  std::optional<AxisOrder> reorder;
  if (const std::string* d = image->attribute("Direction")) {
    VOXLINK_ASSIGN_OR_RETURN(std::vector<double> m, parseDoubles(*d, path, "Direction", 9));
    for (int a = 0; a < 3; ++a) axes[a] = {m[a], m[3 + a], m[6 + a]};  // columns are the axes
    reorder = axisOrderOf(axes);
    if (reorder && reorder->identity()) reorder.reset();
    if (reorder) {
      std::string along;
      for (int a = 0; a < 3; ++a)
        along += cat(a ? " " : "", reorder->reversed[a] ? "-" : "+", "xyz"[reorder->worldAxis[a]]);
      info.notes.push_back(cat("Direction axes run along ", along,
                               ": voxels reordered to run along +x +y +z (world positions kept)"));
    } else if (const AxesSummary sum = summarizeAxes(axes, "Direction axes"); !sum.note.empty()) {
      info.notes.push_back(sum.note);  // oblique: index order, lengths as spacing
    }
  }
  // Voxel (0,0,0) is the extent's minimum index (its maximum along a reversed axis):
  // origin + direction * (index * spacing).
  for (int c = 0; c < 3; ++c) {
    info.origin[c] = origin[c];
    for (int a = 0; a < 3; ++a) {
      const int64_t first = reorder && reorder->reversed[a] ? extent[2 * a + 1] : extent[2 * a];
      info.origin[c] += axes[a][c] * static_cast<double>(first) * info.spacing[a];
    }
  }
  if (reorder) {  // one step along grid axis a is a step of spacing * |direction| in the world
    const std::array<double, 3> spacing = info.spacing;
    for (int a = 0; a < 3; ++a) info.spacing[reorder->worldAxis[a]] = spacing[a] * length(axes[a]);
  }

  const size_t pieceAt = header.find("Piece", imageAt + 1);
  if (pieceAt == XmlHeader::kNone)
    return makeError(ErrorCode::kCorrupt, path, ": no <Piece> element");
  const XmlTag* piece = &header[pieceAt];
  if (piece->attribute("Extent") && trim(*piece->attribute("Extent")) != trim(extentText))
    return makeError(ErrorCode::kUnsupported, path,
                     ": Piece attribute 'Extent' differs from WholeExtent (several pieces)");
  const size_t pointData = header.find("PointData", pieceAt + 1);
  if (pointData == XmlHeader::kNone || !header[pointData].hasChildren)
    return makeError(ErrorCode::kUnsupported, path,
                     ": no <PointData> arrays (cell data is not supported)");
  VOXLINK_ASSIGN_OR_RETURN(const XmlTag chosen,
                           pickArray(header, pointData, options.variable, path, info.notes));
  const XmlTag* array = &chosen;
  VOXLINK_ASSIGN_OR_RETURN(info.type,
                           vtkType(requireAttribute(*array, "type", status, path), path));
  VOXLINK_RETURN_IF_ERROR(status);
  layout.expected = info.voxelCount() * scalarSize(info.type);

  const std::string format = requireAttribute(*array, "format", status, path);
  VOXLINK_RETURN_IF_ERROR(status);
  // Where the encoded array starts, and whether it is base64 or raw bytes.
  std::string_view encoded;
  bool base64 = true;
  if (format == "binary") {
    encoded = trim(array->text);
  } else if (format == "appended") {
    VOXLINK_ASSIGN_OR_RETURN(
        int64_t offset,
        parseInteger(requireAttribute(*array, "offset", status, path), path, "offset"));
    VOXLINK_RETURN_IF_ERROR(status);
    const size_t appendedAt = header.find("AppendedData", header[pointData].subtreeEnd);
    if (appendedAt == XmlHeader::kNone)
      return makeError(ErrorCode::kCorrupt, path, ": no <AppendedData> for an appended DataArray");
    const XmlTag* appended = &header[appendedAt];
    const size_t underscore = appended->textBegin == XmlHeader::kNone
                                  ? std::string::npos
                                  : xml.find('_', appended->textBegin);
    if (underscore == std::string::npos || offset < 0 ||
        underscore + 1 + static_cast<uint64_t>(offset) > xml.size())
      return makeError(ErrorCode::kCorrupt, path, ": AppendedData: no '_' marker or offset ",
                       offset, " beyond the file");
    encoded = std::string_view(xml).substr(underscore + 1 + static_cast<size_t>(offset));
    base64 = appended->attribute("encoding") && *appended->attribute("encoding") == "base64";
  } else {
    return makeError(ErrorCode::kUnsupported, path, ": DataArray attribute 'format': ", format,
                     " (binary and appended are supported)");
  }
  std::vector<uint8_t> decoded;  // uncompressed base64: header and data are one encoded run
  if (base64 && !layout.compressed) {
    const size_t chars = base64Length(layout.headerWord + layout.expected);
    if (chars > encoded.size())
      return makeError(ErrorCode::kTruncated, path, ": DataArray: encoded data ends early");
    VOXLINK_ASSIGN_OR_RETURN(decoded, decodeBase64(encoded.substr(0, chars), path));
    encoded = std::string_view(reinterpret_cast<const char*>(decoded.data()), decoded.size());
    base64 = false;
  }
  // Compressed base64 data encodes the header and the blocks as separate runs; the header's first
  // three words are a multiple of 3 bytes, so it can be decoded in two steps.
  auto next = [&](uint64_t bytes) -> Result<std::vector<uint8_t>> {
    const size_t chars = base64 ? base64Length(bytes) : bytes;
    if (chars > encoded.size())
      return makeError(ErrorCode::kTruncated, path, ": DataArray: encoded data ends early");
    std::vector<uint8_t> out;
    if (base64) {
      VOXLINK_ASSIGN_OR_RETURN(out, decodeBase64(encoded.substr(0, chars), path));
      out.resize(bytes);
    } else {
      out.assign(encoded.begin(), encoded.begin() + static_cast<long>(chars));
    }
    encoded.remove_prefix(chars);
    if (base64) encoded = trim(encoded);
    return out;
  };
  VOXLINK_ASSIGN_OR_RETURN(std::vector<uint8_t> data, decodeArray(next, layout));
  if (data.size() != layout.expected)
    return makeError(ErrorCode::kSizeMismatch, path, ": DataArray: ", data.size(),
                     " bytes, the extent needs ", layout.expected);
  if (layout.bigEndian) swapBytesInPlace(data.data(), info.voxelCount(), scalarSize(info.type));
  if (reorder) {
    VOXLINK_ASSIGN_OR_RETURN(
        data, reorderToWorldAxes(data, info.dims, scalarSize(info.type), *reorder, path));
  }
  info.notes.push_back("VTK XML data is decoded whole at open and served from memory");
  VOXLINK_RETURN_IF_ERROR(applyOpenOptions(info, options));
  return std::unique_ptr<VolumeSource>(new MemorySource(std::move(info), std::move(data)));
}

}  // namespace voxlink::sources
