// SPDX-License-Identifier: BSD-3-Clause
#include "sources/readers/gslib_reader.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <sstream>

#include "sources/readers/detail/text_stream.h"
#include "sources/readers/reader_common.h"

namespace voxlink::sources {
namespace {

std::string lowerCopy(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

std::string trimmed(std::string_view s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
  return std::string(s);
}

// Three positive integers and nothing else, as SGeMS writes grid titles.
std::optional<std::array<uint32_t, 3>> dimsFromTitle(const std::string& title) {
  std::istringstream in(title);
  std::array<uint32_t, 3> dims{};
  for (auto& d : dims) {
    long long v = 0;
    if (!(in >> v) || v < 1 || v > UINT32_MAX) return std::nullopt;
    d = static_cast<uint32_t>(v);
  }
  std::string rest;
  if (in >> rest) return std::nullopt;
  return dims;
}

struct GslibHeader {
  std::string title;
  std::vector<std::string> names;
  uint64_t headerLines = 0;
};

Result<GslibHeader> readHeader(TextStream& s) {
  GslibHeader h;
  std::string_view line;
  VOXLINK_ASSIGN_OR_RETURN(bool ok, s.nextLine(line));
  if (!ok) return makeError(ErrorCode::kTruncated, s.name(), ": GSLIB header: empty file");
  if (line.find('\0') != std::string_view::npos)
    return makeError(ErrorCode::kUnsupported, s.name(),
                     ": GSLIB header: binary data (an SGeMS binary object file?); export the grid "
                     "from SGeMS as GSLIB text");
  h.title = trimmed(line);
  VOXLINK_ASSIGN_OR_RETURN(ok, s.nextLine(line));
  const std::string count = ok ? trimmed(line) : "";
  char* end = nullptr;
  const long n = std::strtol(count.c_str(), &end, 10);
  if (!ok || count.empty() || *end != '\0' || n < 1 || n > 10000)
    return makeError(
        ErrorCode::kCorrupt, s.name(),
        ": GSLIB header line 2 'number of variables': expected an integer in 1..10000, got '",
        count, "'");
  for (long i = 0; i < n; ++i) {
    VOXLINK_ASSIGN_OR_RETURN(ok, s.nextLine(line));
    if (!ok)
      return makeError(ErrorCode::kTruncated, s.name(), ": GSLIB header: ", n,
                       " variable names announced, the file ends after ", i);
    h.names.push_back(trimmed(line));
  }
  h.headerLines = s.lineNumber();
  return h;
}

class GslibSource final : public VolumeSource {
 public:
  GslibSource(VolumeInfo info, std::unique_ptr<TextStream> stream, GslibHeader header,
              size_t column)
      : stream_(std::move(stream)), header_(std::move(header)), column_(column) {
    info_ = std::move(info);
  }

  Status rewind() override {
    VOXLINK_RETURN_IF_ERROR(stream_->rewind());
    VOXLINK_ASSIGN_OR_RETURN(header_, readHeader(*stream_));
    nextSlice_ = 0;
    return Status::ok();
  }

  Status read(uint32_t z0, uint32_t count, void* dst) override {
    VOXLINK_RETURN_IF_ERROR(checkSliceRange(z0, count));
    if (z0 < nextSlice_) VOXLINK_RETURN_IF_ERROR(rewind());
    while (nextSlice_ < z0) {  // skip to z0 (sequential format)
      VOXLINK_RETURN_IF_ERROR(parseValues(info_.sliceVoxels(), nullptr));
      ++nextSlice_;
    }
    VOXLINK_RETURN_IF_ERROR(
        parseValues(uint64_t{count} * info_.sliceVoxels(), static_cast<double*>(dst)));
    nextSlice_ += count;
    return Status::ok();
  }

  // Reads `n` data rows (skipping blank lines), storing the selected column when out is set.
  Status parseValues(uint64_t n, double* out) {
    std::string_view line;
    for (uint64_t i = 0; i < n;) {
      VOXLINK_ASSIGN_OR_RETURN(const bool ok, stream_->nextLine(line));
      if (!ok)
        return makeError(ErrorCode::kTruncated, stream_->name(),
                         ": GSLIB data: the file ends at line ", stream_->lineNumber(), ", ",
                         info_.voxelCount(), " rows (", info_.dims[0], "x", info_.dims[1], "x",
                         info_.dims[2], ") expected");
      const char* p = line.data();
      const char* end = p + line.size();
      while (p < end && std::isspace(static_cast<unsigned char>(*p))) ++p;
      if (p == end) continue;
      double v = 0;
      for (size_t c = 0; c <= column_; ++c) {
        while (p < end && std::isspace(static_cast<unsigned char>(*p))) ++p;
        const char* start = p;
        while (p < end && !std::isspace(static_cast<unsigned char>(*p))) ++p;
        if (start == p)
          return makeError(ErrorCode::kCorrupt, stream_->name(), ": line ", stream_->lineNumber(),
                           ": ", c, " values, column '", header_.names[column_], "' (", column_ + 1,
                           ") missing");
        if (c == column_) {
          const std::string field(start, p);
          char* stop = nullptr;
          v = std::strtod(field.c_str(), &stop);
          if (*stop != '\0')
            return makeError(ErrorCode::kCorrupt, stream_->name(), ": line ", stream_->lineNumber(),
                             ": column '", header_.names[column_], "': '", field,
                             "' is not a number");
        }
      }
      // Every row holds every variable: a short row would shift the columns of the rows after
      // it in any other reader, and here it hid a damaged file.
      size_t fields = column_ + 1;
      for (;;) {
        while (p < end && std::isspace(static_cast<unsigned char>(*p))) ++p;
        if (p == end) break;
        while (p < end && !std::isspace(static_cast<unsigned char>(*p))) ++p;
        ++fields;
      }
      if (fields != header_.names.size())
        return makeError(ErrorCode::kCorrupt, stream_->name(), ": line ", stream_->lineNumber(),
                         ": ", fields, " values, the header declares ", header_.names.size(),
                         " variables");
      if (out) out[i] = v;
      ++i;
    }
    return Status::ok();
  }

 private:
  std::unique_ptr<TextStream> stream_;
  GslibHeader header_;
  size_t column_;
  uint32_t nextSlice_ = 0;
};

}  // namespace

bool looksLikeGslib(const std::string& path) {
  const std::string name = lowerCopy(path);
  for (const char* ext : {".sgems", ".gslib", ".geoeas", ".sgems.zip", ".gslib.zip"})
    if (name.ends_with(ext)) return true;
  return false;
}

Result<std::unique_ptr<VolumeSource>> openGslib(const std::string& path,
                                                const OpenOptions& options) {
  VOXLINK_ASSIGN_OR_RETURN(std::unique_ptr<TextStream> stream, openTextStream(path));
  VOXLINK_ASSIGN_OR_RETURN(GslibHeader header, readHeader(*stream));
  std::string all;
  bool hasX = false, hasY = false;
  for (const auto& n : header.names) {
    all += (all.empty() ? "" : ", ") + n;
    hasX |= lowerCopy(n) == "x";
    hasY |= lowerCopy(n) == "y";
  }
  if (hasX && hasY)
    return makeError(ErrorCode::kUnsupported, path, ": GEO-EAS point set (columns ", all,
                     "), not a grid: krige it onto a grid with `voxlink krige ", path,
                     " --value NAME ...`");
  size_t column = 0;
  VolumeInfo info;
  info.path = path;
  if (!options.variable.empty()) {
    const auto it = std::find_if(
        header.names.begin(), header.names.end(),
        [&](const std::string& n) { return lowerCopy(n) == lowerCopy(options.variable); });
    if (it == header.names.end())
      return makeError(ErrorCode::kInvalidArgument, path, ": GSLIB variable '", options.variable,
                       "' not found (variables: ", all, ")");
    column = static_cast<size_t>(it - header.names.begin());
  } else if (header.names.size() > 1) {
    info.notes.push_back(
        cat("GSLIB variables ", all, ": using the first, '", header.names[0], "'"));
  }
  const auto titleDims = dimsFromTitle(header.title);
  if (titleDims && options.dims && *titleDims != *options.dims)
    return makeError(ErrorCode::kSizeMismatch, path, ": GSLIB title '", header.title,
                     "' gives dims ", (*titleDims)[0], "x", (*titleDims)[1], "x", (*titleDims)[2],
                     ", --dims says ", (*options.dims)[0], "x", (*options.dims)[1], "x",
                     (*options.dims)[2]);
  if (!titleDims && !options.dims)
    return makeError(ErrorCode::kInvalidArgument, path, ": GSLIB title '", header.title,
                     "' does not give the grid size (\"nx ny nz\"); pass --dims X,Y,Z");
  info.dims = titleDims ? *titleDims : *options.dims;
  if (Status s = checkVolumeShape(info, titleDims ? "title" : "--dims"); !s)
    return Error{titleDims ? ErrorCode::kCorrupt : ErrorCode::kInvalidArgument, s.message()};
  if (options.type && *options.type != ScalarType::kF64)
    return makeError(ErrorCode::kInvalidArgument, path, ": GSLIB values are read as f64; --type ",
                     scalarName(*options.type), " cannot apply");
  info.type = ScalarType::kF64;
  if (options.spacing) info.spacing = *options.spacing;
  info.path = path;
  info.format = "gslib";
  // Count the data rows now, so a wrong size fails at open rather than mid-conversion.
  uint64_t rows = 0;
  std::string_view line;
  for (;;) {
    VOXLINK_ASSIGN_OR_RETURN(const bool ok, stream->nextLine(line));
    if (!ok) break;
    if (line.find_first_not_of(" \t") != std::string_view::npos) ++rows;
  }
  if (rows != info.voxelCount())
    return makeError(rows < info.voxelCount() ? ErrorCode::kTruncated : ErrorCode::kSizeMismatch,
                     path, ": GSLIB data: ", rows, " rows, the grid ", info.dims[0], "x",
                     info.dims[1], "x", info.dims[2], " needs ", info.voxelCount());
  VOXLINK_RETURN_IF_ERROR(stream->rewind());
  VOXLINK_RETURN_IF_ERROR(readHeader(*stream).status());
  return std::unique_ptr<VolumeSource>(
      new GslibSource(std::move(info), std::move(stream), std::move(header), column));
}

}  // namespace voxlink::sources
