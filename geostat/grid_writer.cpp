// SPDX-License-Identifier: BSD-3-Clause
#include "geostat/grid_writer.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <utility>
#include <vector>

#include "base/file_name.h"
#include "base/output_file.h"

namespace voxlink::geostat {
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
  if (base::hasExtension(path, ".nhdr")) return {path, path.substr(0, path.size() - 5) + ".raw"};
  return {path};
}

namespace {

// Checks the type and the name's ending; sets the paths and where the data starts.
Status describe(const std::string& path, const GridFileInfo& info, std::string& dataPath,
                bool& nrrd, uint64_t& dataOffset) {
  if (info.type != ScalarType::kF64 && info.type != ScalarType::kF32)
    return makeError(ErrorCode::kInvalidArgument, path, ": output type must be f32 or f64, got ",
                     scalarName(info.type));
  if (!base::hasExtension(path, ".nhdr") && !base::hasExtension(path, ".npy"))
    return makeError(ErrorCode::kInvalidArgument, path,
                     ": output name must end in .nhdr (raw + NRRD header) or .npy");
  nrrd = base::hasExtension(path, ".nhdr");
  dataPath = GridWriter::filesOf(path).back();  // the .raw beside an .nhdr, or the .npy itself
  dataOffset = nrrd ? 0 : npyHeader(info.type, info.dims).size();
  return Status::ok();
}

Status writeAt(int fd, const void* data, uint64_t bytes, uint64_t offset, const std::string& path) {
  const auto* at = static_cast<const uint8_t*>(data);
  while (bytes > 0) {
    const ssize_t n =
        ::pwrite(fd, at, std::min<uint64_t>(bytes, uint64_t{1} << 30), static_cast<off_t>(offset));
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return makeError(ErrorCode::kIo, path, ": write failed: ", std::strerror(errno));
    at += n, bytes -= static_cast<uint64_t>(n), offset += static_cast<uint64_t>(n);
  }
  return Status::ok();
}

}  // namespace

Result<std::unique_ptr<GridWriter>> GridWriter::create(const std::string& path,
                                                       const GridFileInfo& info) {
  std::unique_ptr<GridWriter> w(new GridWriter);
  w->path_ = path;
  w->info_ = info;
  VOXLINK_RETURN_IF_ERROR(describe(path, info, w->dataPath_, w->nrrd_, w->dataOffset_));
  for (const std::string& file : filesOf(path))
    VOXLINK_RETURN_IF_ERROR(base::checkOutputTarget(file));
  // A unique O_EXCL temporary (never a fixed name a symlink could be planted at); the data and
  // the header are renamed into place together by finish().
  VOXLINK_ASSIGN_OR_RETURN(base::TempFile temp, base::createTempBeside(w->dataPath_));
  w->tempPath_ = temp.path;
  w->fd_ = temp.fd;
  return w;
}

Result<std::unique_ptr<GridWriter>> GridWriter::attach(const std::string& path,
                                                       const std::string& tempPath,
                                                       const GridFileInfo& info) {
  std::unique_ptr<GridWriter> w(new GridWriter);
  w->path_ = path;
  w->info_ = info;
  w->attached_ = true;
  VOXLINK_RETURN_IF_ERROR(describe(path, info, w->dataPath_, w->nrrd_, w->dataOffset_));
  w->fd_ = ::open(tempPath.c_str(), O_WRONLY | O_CLOEXEC);
  if (w->fd_ < 0)
    return makeError(ErrorCode::kIo, w->dataPath_, ": cannot open the shared temporary ", tempPath,
                     ": ", std::strerror(errno));
  w->tempPath_ = tempPath;
  return w;
}

GridWriter::~GridWriter() {
  if (fd_ >= 0) ::close(fd_);
  if (!tempPath_.empty() && !attached_) base::discardTemp(tempPath_);
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
  const uint64_t sliceNodes = uint64_t{info_.dims[0]} * info_.dims[1];
  return write(nodesWritten_, sliceNodes * count, slices);
}

Status GridWriter::write(uint64_t firstNode, uint64_t nodes, const double* values) {
  const uint64_t total = uint64_t{info_.dims[0]} * info_.dims[1] * info_.dims[2];
  if (fd_ < 0 || firstNode > total || nodes > total - firstNode)
    return makeError(ErrorCode::kInvalidArgument, path_, ": nodes ", firstNode, "..",
                     firstNode + nodes, " are not in the grid of ", total);
  if (info_.type == ScalarType::kF64) {
    VOXLINK_RETURN_IF_ERROR(checkFinite(values, nodes, firstNode, info_, path_));
    VOXLINK_RETURN_IF_ERROR(writeAt(fd_, values, nodes * sizeof(double),
                                    dataOffset_ + firstNode * sizeof(double), dataPath_));
  } else {  // converted a piece at a time: a whole 2-D grid's run held twice cost 4 B a node
    std::vector<float> f;
    for (uint64_t done = 0; done < nodes; done += f.size()) {
      f.assign(values + done, values + done + std::min<uint64_t>(nodes - done, 1 << 20));
      VOXLINK_RETURN_IF_ERROR(checkFinite(f.data(), f.size(), firstNode + done, info_, path_));
      VOXLINK_RETURN_IF_ERROR(writeAt(fd_, f.data(), f.size() * sizeof(float),
                                      dataOffset_ + (firstNode + done) * sizeof(float), dataPath_));
    }
  }
  nodesWritten_ += nodes;
  return Status::ok();
}

Status GridWriter::close() {
  const int fd = std::exchange(fd_, -1);
  if (fd >= 0 && ::close(fd) != 0)
    return makeError(ErrorCode::kIo, dataPath_, ": write failed: ", std::strerror(errno));
  return Status::ok();
}

Status GridWriter::finish(uint64_t nodesWrittenByAll) {
  const uint64_t total = uint64_t{info_.dims[0]} * info_.dims[1] * info_.dims[2];
  if (attached_ || nodesWrittenByAll != total)
    return makeError(ErrorCode::kInvalidArgument, path_, ": ", nodesWrittenByAll,
                     " nodes written, ", total, " expected");
  if (!nrrd_) {
    const std::string header = npyHeader(info_.type, info_.dims);
    VOXLINK_RETURN_IF_ERROR(writeAt(fd_, header.data(), header.size(), 0, dataPath_));
  }
  VOXLINK_RETURN_IF_ERROR(close());
  if (!nrrd_) return base::commitTemp(std::exchange(tempPath_, std::string()), dataPath_);
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
  VOXLINK_ASSIGN_OR_RETURN(base::TempFile header, base::createTempBeside(path_));
  std::FILE* h = fdopen(header.fd, "w");
  const bool wrote = h && std::fputs(text.c_str(), h) >= 0;
  const bool closed = h ? std::fclose(h) == 0 : ::close(header.fd) == 0;
  if (!wrote || !closed) {
    base::discardTemp(header.path);
    return makeError(ErrorCode::kIo, path_, ": write failed: ", std::strerror(errno));
  }
  // Both files are complete: the data, then the header that names it, are moved into place.
  if (Status data = base::commitTemp(std::exchange(tempPath_, std::string()), dataPath_); !data) {
    base::discardTemp(header.path);
    return data;
  }
  return base::commitTemp(header.path, path_);
}

}  // namespace voxlink::geostat
