// SPDX-License-Identifier: BSD-3-Clause
#include "sources/readers/npy_reader.h"

#include <cstring>
#include <fstream>

#include "base/mapped_file.h"
#include "sources/readers/detail/byte_order.h"
#include "sources/readers/raw_reader.h"
#include "sources/readers/reader_common.h"

namespace voxlink::sources {
namespace {

constexpr char kMagic[] = "\x93NUMPY";
constexpr size_t kMagicSize = 6;

// A strict reader of the Python dict literal numpy writes:
// {'descr': '<f8', 'fortran_order': False, 'shape': (3, 4), }
class DictParser {
 public:
  DictParser(const std::string& text, const std::string& path) : s_(text), path_(path) {}

  Status parse(NpyHeader& h) {
    bool haveDescr = false, haveOrder = false, haveShape = false;
    skipSpace();
    VOXLINK_RETURN_IF_ERROR(expect('{'));
    for (;;) {
      skipSpace();
      if (peek() == '}') {
        ++pos_;
        break;
      }
      VOXLINK_ASSIGN_OR_RETURN(const std::string key, parseString("a key"));
      skipSpace();
      VOXLINK_RETURN_IF_ERROR(expect(':'));
      skipSpace();
      if (key == "descr") {
        if (haveDescr) return fail("descr", "appears twice");
        if (peek() == '[')
          return fail("descr", "structured dtypes (a list of fields) are not supported");
        VOXLINK_ASSIGN_OR_RETURN(h.descr, parseString("'descr'"));
        haveDescr = true;
      } else if (key == "fortran_order") {
        if (haveOrder) return fail("fortran_order", "appears twice");
        if (s_.compare(pos_, 4, "True") == 0) {
          h.fortranOrder = true;
          pos_ += 4;
        } else if (s_.compare(pos_, 5, "False") == 0) {
          h.fortranOrder = false;
          pos_ += 5;
        } else
          return fail("fortran_order", "expected True or False, got '" + s_.substr(pos_, 8) + "'");
        haveOrder = true;
      } else if (key == "shape") {
        if (haveShape) return fail("shape", "appears twice");
        VOXLINK_RETURN_IF_ERROR(parseShape(h.shape));
        haveShape = true;
      } else {
        return fail(key, "unknown key (expected only descr, fortran_order, shape)");
      }
      skipSpace();
      if (peek() == ',') {
        ++pos_;
        continue;
      }
      skipSpace();
      if (peek() != '}')
        return fail("header", cat("expected ',' or '}' at offset ", pos_, ", got '",
                                  s_.substr(pos_, 8), "'"));
    }
    skipSpace();
    if (pos_ != s_.size())
      return fail("header", cat("trailing characters after the dict: '", s_.substr(pos_, 16), "'"));
    if (!haveDescr) return fail("descr", "missing");
    if (!haveOrder) return fail("fortran_order", "missing");
    if (!haveShape) return fail("shape", "missing");
    return Status::ok();
  }

 private:
  char peek() const { return pos_ < s_.size() ? s_[pos_] : '\0'; }
  void skipSpace() {
    while (pos_ < s_.size() && (s_[pos_] == ' ' || s_[pos_] == '\t' || s_[pos_] == '\n')) ++pos_;
  }
  Error fail(const std::string& field, const std::string& what) const {
    return makeError(ErrorCode::kCorrupt, path_, ": npy header field '", field, "': ", what);
  }
  Status expect(char c, const char* field = "header") {
    if (peek() != c)
      return fail(field,
                  cat("expected '", c, "' at offset ", pos_, ", got '", s_.substr(pos_, 8), "'"));
    ++pos_;
    return Status::ok();
  }
  Result<std::string> parseString(const char* what) {
    const char quote = peek();
    if (quote != '\'' && quote != '"')
      return fail("header", cat("expected a quoted string for ", what, " at offset ", pos_));
    const size_t end = s_.find(quote, pos_ + 1);
    if (end == std::string::npos) return fail("header", cat("unterminated string for ", what));
    std::string out = s_.substr(pos_ + 1, end - pos_ - 1);
    pos_ = end + 1;
    return out;
  }
  Status parseShape(std::vector<uint64_t>& shape) {
    VOXLINK_RETURN_IF_ERROR(expect('(', "shape"));
    for (;;) {
      skipSpace();
      if (peek() == ')') {
        ++pos_;
        return Status::ok();
      }
      if (!std::isdigit(static_cast<unsigned char>(peek())))
        return fail("shape", cat("expected a non-negative integer at offset ", pos_, ", got '",
                                 s_.substr(pos_, 8), "'"));
      uint64_t v = 0;
      while (std::isdigit(static_cast<unsigned char>(peek()))) {
        if (v > (uint64_t{1} << 50)) return fail("shape", "dimension too large");
        v = v * 10 + static_cast<uint64_t>(s_[pos_++] - '0');
      }
      if (peek() == 'L') ++pos_;  // Python 2 long literal, as old numpy wrote it
      shape.push_back(v);
      skipSpace();
      if (peek() == ',') {
        ++pos_;
        continue;
      }
      if (peek() != ')') return fail("shape", cat("expected ',' or ')' at offset ", pos_));
    }
  }

  const std::string& s_;
  const std::string& path_;
  size_t pos_ = 0;
};

Result<std::pair<ScalarType, Endian>> parseDescr(const std::string& descr,
                                                 const std::string& path) {
  auto bad = [&](const std::string& why) {
    return makeError(ErrorCode::kUnsupported, path, ": npy header field 'descr': '", descr, "' ",
                     why, " (supported: u1 i1 u2 i2 u4 i4 f4 f8 with <, > or |)");
  };
  if (descr.size() < 3) return bad("is not a dtype string");
  const char order = descr[0];
  const std::string code = descr.substr(1);
  static const std::pair<const char*, ScalarType> kTypes[] = {
      {"u1", ScalarType::kU8},  {"i1", ScalarType::kI8},  {"u2", ScalarType::kU16},
      {"i2", ScalarType::kI16}, {"u4", ScalarType::kU32}, {"i4", ScalarType::kI32},
      {"f4", ScalarType::kF32}, {"f8", ScalarType::kF64}};
  for (const auto& [name, type] : kTypes) {
    if (code != name) continue;
    if (order == '|' && scalarSize(type) != 1) return bad("has no byte order but is multi-byte");
    if (order != '<' && order != '>' && order != '|' && order != '=')
      return bad("has an unknown byte-order character");
    const Endian native = kHostIsLittleEndian ? Endian::kLittle : Endian::kBig;
    return std::make_pair(type, order == '>'   ? Endian::kBig
                                : order == '<' ? Endian::kLittle
                                               : native);
  }
  return bad("is not a supported type");
}

// Serves a Fortran-order array: element (x, y, z) lies at z + nz * (y + ny * x).
class FortranNpySource final : public VolumeSource {
 public:
  FortranNpySource(VolumeInfo info, base::MappedFile file, uint64_t offset, bool swap)
      : file_(std::move(file)), offset_(offset), swap_(swap) {
    info_ = std::move(info);
  }
  bool randomAccess() const override { return true; }

  Status read(uint32_t z0, uint32_t count, void* dst) override {
    VOXLINK_RETURN_IF_ERROR(checkSliceRange(z0, count));
    const auto& d = info_.dims;
    const size_t e = scalarSize(info_.type);
    auto* out = static_cast<uint8_t*>(dst);
    const uint8_t* base = file_.data() + offset_;
    // Runs along z are contiguous in the file: copy each run into its place in every slice.
    for (uint64_t x = 0; x < d[0]; ++x)
      for (uint64_t y = 0; y < d[1]; ++y) {
        const uint8_t* run = base + ((x * d[1] + y) * d[2] + z0) * e;
        for (uint32_t k = 0; k < count; ++k)
          std::memcpy(out + ((uint64_t{k} * d[1] + y) * d[0] + x) * e, run + uint64_t{k} * e, e);
      }
    if (swap_) swapBytesInPlace(dst, count * info_.sliceVoxels(), e);
    return Status::ok();
  }

 private:
  base::MappedFile file_;
  uint64_t offset_;
  bool swap_;
};

}  // namespace

bool hasNpyMagic(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  char magic[kMagicSize] = {};
  in.read(magic, kMagicSize);
  return in.gcount() == static_cast<std::streamsize>(kMagicSize) &&
         std::memcmp(magic, kMagic, kMagicSize) == 0;
}

Result<NpyHeader> parseNpyHeader(const uint8_t* bytes, uint64_t size, const std::string& path) {
  if (size < 10)
    return makeError(ErrorCode::kTruncated, path, ": npy preamble: file has ", size,
                     " bytes, fewer than the 10-byte preamble");
  if (std::memcmp(bytes, kMagic, kMagicSize) != 0)
    return makeError(ErrorCode::kCorrupt, path, ": npy magic: expected \\x93NUMPY");
  NpyHeader h;
  h.majorVersion = bytes[6];
  h.minorVersion = bytes[7];
  uint64_t headerLength = 0, lengthBytes = 0;
  if (h.majorVersion == 1) {
    headerLength = bytes[8] | (uint64_t{bytes[9]} << 8);
    lengthBytes = 2;
  } else if (h.majorVersion == 2 || h.majorVersion == 3) {
    if (size < 12)
      return makeError(ErrorCode::kTruncated, path, ": npy preamble: version ", h.majorVersion,
                       " needs 12 bytes, file has ", size);
    headerLength = bytes[8] | (uint64_t{bytes[9]} << 8) | (uint64_t{bytes[10]} << 16) |
                   (uint64_t{bytes[11]} << 24);
    lengthBytes = 4;
  } else {
    return makeError(ErrorCode::kUnsupported, path, ": npy version: ", h.majorVersion, ".",
                     h.minorVersion, " (supported: 1.0, 2.0, 3.0)");
  }
  if (h.minorVersion != 0)
    return makeError(ErrorCode::kUnsupported, path, ": npy version: ", h.majorVersion, ".",
                     h.minorVersion, " (supported: 1.0, 2.0, 3.0)");
  h.dataOffset = 8 + lengthBytes + headerLength;
  if (h.dataOffset > size)
    return makeError(ErrorCode::kTruncated, path, ": npy header length: ", headerLength,
                     " bytes announced, the file has only ", size - 8 - lengthBytes,
                     " after the preamble");
  std::string text(reinterpret_cast<const char*>(bytes + 8 + lengthBytes), headerLength);
  if (text.empty() || text.back() != '\n')
    return makeError(ErrorCode::kCorrupt, path, ": npy header: must end with a newline");
  if (text.find('\0') != std::string::npos)
    return makeError(ErrorCode::kCorrupt, path, ": npy header: contains a NUL byte");
  VOXLINK_RETURN_IF_ERROR(DictParser(text, path).parse(h));
  VOXLINK_ASSIGN_OR_RETURN(const auto typeAndOrder, parseDescr(h.descr, path));
  h.type = typeAndOrder.first;
  h.endian = typeAndOrder.second;
  // Leading axes beyond three must have size 1; the last three are z, y, x.
  std::vector<uint64_t> shape = h.shape;
  if (shape.empty())
    return makeError(ErrorCode::kUnsupported, path,
                     ": npy header field 'shape': () is a scalar, not a volume");
  while (shape.size() > 3) {
    if (shape.front() != 1)
      return makeError(ErrorCode::kUnsupported, path, ": npy header field 'shape': ", shape.size(),
                       " axes; only 1 to 3 (plus leading axes of size 1) are volumes");
    shape.erase(shape.begin());
  }
  for (size_t i = 0; i < shape.size(); ++i) {
    if (shape[i] == 0 || shape[i] > UINT32_MAX)
      return makeError(ErrorCode::kInvalidArgument, path, ": npy header field 'shape': axis ", i,
                       " has size ", shape[i], " (must be 1..", UINT32_MAX, ")");
    h.dims[shape.size() - 1 - i] = static_cast<uint32_t>(shape[i]);
  }
  return h;
}

Result<std::unique_ptr<VolumeSource>> openNpy(const std::string& path, const OpenOptions& options) {
  VOXLINK_ASSIGN_OR_RETURN(base::MappedFile file, base::MappedFile::open(path));
  VOXLINK_ASSIGN_OR_RETURN(const NpyHeader h, parseNpyHeader(file.data(), file.size(), path));
  VolumeInfo info;
  info.dims = h.dims;
  info.type = h.type;
  info.path = path;
  info.format = "npy";
  if (options.spacing) info.spacing = *options.spacing;
  if (options.dims && *options.dims != info.dims)
    return makeError(ErrorCode::kSizeMismatch, path, ": npy header field 'shape': ", info.dims[0],
                     "x", info.dims[1], "x", info.dims[2], " (x, y, z) disagrees with --dims ",
                     (*options.dims)[0], "x", (*options.dims)[1], "x", (*options.dims)[2]);
  if (options.type && *options.type != info.type)
    return makeError(ErrorCode::kSizeMismatch, path, ": npy header field 'descr': '", h.descr,
                     "' disagrees with --type ", scalarName(*options.type));
  VOXLINK_RETURN_IF_ERROR(checkVolumeShape(info, "shape"));
  const uint64_t needed = info.voxelCount() * scalarSize(info.type);  // bounded by the check
  const uint64_t available = file.size() - h.dataOffset;
  if (available < needed)
    return makeError(ErrorCode::kTruncated, path, ": npy data: shape needs ", needed,
                     " bytes after the ", h.dataOffset, "-byte header, the file has ", available);
  if (available > needed)
    return makeError(ErrorCode::kSizeMismatch, path, ": npy data: shape needs ", needed,
                     " bytes after the ", h.dataOffset, "-byte header, the file has ", available,
                     " (trailing bytes)");
  const bool fortranMatters =
      h.fortranOrder && ((info.dims[0] > 1) + (info.dims[1] > 1) + (info.dims[2] > 1) > 1);
  if (!fortranMatters) {
    if (h.fortranOrder)
      info.notes.push_back("Fortran order on a 1-D array: same layout as C order");
    return openRawData(path, std::move(info), h.endian, h.dataOffset, false);
  }
  info.notes.push_back("Fortran-order array: slices are gathered from the whole file on each read");
  const bool swap =
      scalarSize(info.type) > 1 && ((h.endian == Endian::kLittle) != kHostIsLittleEndian);
  return std::unique_ptr<VolumeSource>(
      new FortranNpySource(std::move(info), std::move(file), h.dataOffset, swap));
}

}  // namespace voxlink::sources
