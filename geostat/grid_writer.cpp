#include "geostat/grid_writer.h"

#include <unistd.h>

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <utility>
#include <vector>

#include "format/file_name.h"
#include "format/output_file.h"

namespace voxlink::kriging {
namespace {

// Shortest text that reads back to the same double: UTM-sized origins survive the header.
std::string num(double v) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

}  // namespace

std::string npyHeader(ScalarType type, std::array<uint32_t, 3> dims) {
  std::string dict =
      cat("{'descr': '", type == ScalarType::kF32 ? "<f4" : "<f8",
          "', 'fortran_order': False, 'shape': (", dims[2], ", ", dims[1], ", ", dims[0], "), }");
  const size_t fixed = 10;  // magic (6) + version (2) + header length (2)
  size_t total = fixed + dict.size() + 1;
  total = (total + 63) / 64 * 64;
  dict.append(total - fixed - dict.size() - 1, ' ');
  dict += '\n';
  std::string header("\x93NUMPY\x01\x00", 8);
  header += static_cast<char>(dict.size() & 0xff);
  header += static_cast<char>(dict.size() >> 8);
  return header + dict;
}

std::vector<std::string> GridWriter::filesOf(const std::string& path) {
  if (format::hasExtension(path, ".nhdr")) return {path, path.substr(0, path.size() - 5) + ".raw"};
  return {path};
}

Result<std::unique_ptr<GridWriter>> GridWriter::create(const std::string& path,
                                                       const GridFileInfo& info) {
  if (info.type != ScalarType::kF64 && info.type != ScalarType::kF32)
    return makeError(ErrorCode::kInvalidArgument, path, ": output type must be f32 or f64, got ",
                     scalarName(info.type));
  std::unique_ptr<GridWriter> w(new GridWriter);
  w->path_ = path;
  w->info_ = info;
  if (!format::hasExtension(path, ".nhdr") && !format::hasExtension(path, ".npy"))
    return makeError(ErrorCode::kInvalidArgument, path,
                     ": output name must end in .nhdr (raw + NRRD header) or .npy");
  w->nrrd_ = format::hasExtension(path, ".nhdr");
  const std::vector<std::string> files = filesOf(path);
  w->dataPath_ = files.back();  // the .raw beside an .nhdr, or the .npy itself
  for (const std::string& file : files) VOXLINK_RETURN_IF_ERROR(format::checkOutputTarget(file));
  // A unique O_EXCL temporary (never a fixed name a symlink could be planted at); the data and
  // the header are renamed into place together by finish().
  VOXLINK_ASSIGN_OR_RETURN(format::TempFile temp, format::createTempBeside(w->dataPath_));
  w->tempPath_ = temp.path;
  w->file_ = fdopen(temp.fd, "wb");
  if (!w->file_) {
    ::close(temp.fd);
    format::discardTemp(temp.path);
    return makeError(ErrorCode::kIo, path, ": cannot create: ", std::strerror(errno));
  }
  if (!w->nrrd_) {
    const std::string header = npyHeader(info.type, info.dims);
    if (std::fwrite(header.data(), 1, header.size(), w->file_) != header.size())
      return makeError(ErrorCode::kIo, w->dataPath_, ": write failed: ", std::strerror(errno));
  }
  return w;
}

GridWriter::~GridWriter() {
  if (file_) std::fclose(file_);
  if (!tempPath_.empty()) format::discardTemp(tempPath_);
}

namespace {

// The grid's values must be finite in the file's type, as `voxlink convert` requires: a mean of
// 1e308 written as f32 (inf), or a sill that overflows (NaN), gave a file of non-finite values
// and exit status 0.
template <class T>
Status checkFinite(const T* values, uint64_t n, uint64_t firstIndex, const GridFileInfo& info,
                   const std::string& path) {
  for (uint64_t i = 0; i < n; ++i)
    if (!std::isfinite(values[i])) {
      const uint64_t at = firstIndex + i, nx = info.dims[0], ny = info.dims[1];
      return makeError(ErrorCode::kInvalidArgument, path, ": value ", values[i], " at node (",
                       at % nx, ", ", at / nx % ny, ", ", at / (nx * ny), ") is not finite as ",
                       scalarName(info.type), " (check the mean, the sill and the output type)");
    }
  return Status::ok();
}

}  // namespace

Status GridWriter::append(uint32_t count, const double* slices) {
  const uint64_t n = uint64_t{info_.dims[0]} * info_.dims[1] * count;
  const uint64_t first = uint64_t{info_.dims[0]} * info_.dims[1] * slicesWritten_;
  size_t written;
  if (info_.type == ScalarType::kF64) {
    VOXLINK_RETURN_IF_ERROR(checkFinite(slices, n, first, info_, path_));
    written = std::fwrite(slices, sizeof(double), n, file_);
  } else {
    std::vector<float> f(slices, slices + n);
    VOXLINK_RETURN_IF_ERROR(checkFinite(f.data(), n, first, info_, path_));
    written = std::fwrite(f.data(), sizeof(float), n, file_);
  }
  if (written != n)
    return makeError(ErrorCode::kIo, dataPath_, ": write failed: ", std::strerror(errno));
  slicesWritten_ += count;
  return Status::ok();
}

Status GridWriter::finish() {
  if (slicesWritten_ != info_.dims[2])
    return makeError(ErrorCode::kInvalidArgument, path_, ": ", slicesWritten_, " slices written, ",
                     info_.dims[2], " expected");
  const bool flushed = std::fflush(file_) == 0;
  const bool ok = std::fclose(file_) == 0 && flushed;
  file_ = nullptr;
  if (!ok) return makeError(ErrorCode::kIo, dataPath_, ": write failed: ", std::strerror(errno));
  if (!nrrd_) return format::commitTemp(std::exchange(tempPath_, std::string()), dataPath_);
  const auto& d = info_.dims;
  const auto& s = info_.spacing;
  const auto& o = info_.origin;
  const std::string text =
      cat("NRRD0004\n# written by voxlink (krige or grf)\n",
          "type: ", info_.type == ScalarType::kF32 ? "float" : "double", "\n",
          "dimension: 3\nsizes: ", d[0], " ", d[1], " ", d[2], "\n", "space dimension: 3\n",
          "space directions: (", num(s[0]), ",0,0) (0,", num(s[1]), ",0) (0,0,", num(s[2]), ")\n",
          "space origin: (", num(o[0]), ",", num(o[1]), ",", num(o[2]), ")\n",
          "endian: little\nencoding: raw\n",
          "data file: ", std::filesystem::path(dataPath_).filename().string(), "\n");
  VOXLINK_ASSIGN_OR_RETURN(format::TempFile header, format::createTempBeside(path_));
  std::FILE* h = fdopen(header.fd, "w");
  const bool wrote = h && std::fputs(text.c_str(), h) >= 0;
  const bool closed = h ? std::fclose(h) == 0 : ::close(header.fd) == 0;
  if (!wrote || !closed) {
    format::discardTemp(header.path);
    return makeError(ErrorCode::kIo, path_, ": write failed: ", std::strerror(errno));
  }
  // Both files are complete: the data, then the header that names it, are moved into place.
  if (Status data = format::commitTemp(std::exchange(tempPath_, std::string()), dataPath_); !data) {
    format::discardTemp(header.path);
    return data;
  }
  return format::commitTemp(header.path, path_);
}

}  // namespace voxlink::kriging
