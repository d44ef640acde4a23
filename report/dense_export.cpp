// SPDX-License-Identifier: BSD-3-Clause
#include "report/dense_export.h"

#include <unistd.h>

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <limits>
#include <new>
#include <sstream>
#include <vector>

#include "base/file_name.h"
#include "base/output_file.h"
#include "base/process_memory.h"
#include "format/source_value.h"
#include "format/voxel_locator.h"

namespace voxlink::report {

using format::FileHeader;
using format::VoxelLocator;
using format::VoxLinkFile;

namespace {

const char* nrrdTypeName(ScalarType type) {
  switch (type) {
    case ScalarType::kU8:
      return "uint8";
    case ScalarType::kI8:
      return "int8";
    case ScalarType::kU16:
      return "uint16";
    case ScalarType::kI16:
      return "int16";
    case ScalarType::kU32:
      return "uint32";
    case ScalarType::kI32:
      return "int32";
    case ScalarType::kF32:
      return "float";
    case ScalarType::kF64:
      return "double";
  }
  return nullptr;
}

template <class T>
bool fits(double v) {
  return std::isfinite(v) && v >= double(std::numeric_limits<T>::lowest()) &&
         v <= double(std::numeric_limits<T>::max());
}

bool fillFits(ScalarType type, double v) {
  switch (type) {
    case ScalarType::kU8:
      return fits<uint8_t>(v);
    case ScalarType::kI8:
      return fits<int8_t>(v);
    case ScalarType::kU16:
      return fits<uint16_t>(v);
    case ScalarType::kI16:
      return fits<int16_t>(v);
    case ScalarType::kU32:
      return fits<uint32_t>(v);
    case ScalarType::kI32:
      return fits<int32_t>(v);
    case ScalarType::kF32:
      return fits<float>(v);
    case ScalarType::kF64:
      return std::isfinite(v);
  }
  return false;
}

}  // namespace

Status checkFill(ScalarType type, double fill, const std::string& where, std::string_view option) {
  char text[32];
  const auto end = std::to_chars(text, text + sizeof text, fill).ptr;  // shortest, exact
  const std::string shown(text, end);
  if (!fillFits(type, fill))
    return makeError(ErrorCode::kInvalidArgument, where, ": ", option, " ", shown,
                     " does not fit the source type ", scalarName(type));
  if (type != ScalarType::kF32 && type != ScalarType::kF64 && fill != std::trunc(fill))
    return makeError(ErrorCode::kInvalidArgument, where, ": ", option, " ", shown,
                     " is not a whole number, and the source type ", scalarName(type),
                     " holds only whole numbers");
  return Status::ok();
}

namespace {

// Stores v as the source type at p, rounded and clamped as asSourceValueOf() does (exact for
// files whose stored type is lossless; an f32-stored i32 2147483647 decodes to 2^31).
void store(ScalarType type, double v, uint8_t* p) {
  dispatchScalar(type, [&](auto t) {
    using T = decltype(t);
    const T value = static_cast<T>(asSourceValueOf<T>(v));
    std::memcpy(p, &value, sizeof value);
  });
}

// `dataFile` empty: an attached header (the data follows the blank line); else a detached
// header naming its data file.
std::string nrrdHeader(const VoxLinkFile& file, double fill, const std::string& dataFile) {
  const FileHeader& h = file.header();
  std::ostringstream out;
  out.precision(17);
  out << "NRRD0004\n"
      << "# exported by voxlink from a VoxLink file: stored voxels hold their values, removed "
         "voxels hold "
      << fill << "\n"
      << "type: " << nrrdTypeName(file.sourceType()) << "\n"
      << "dimension: 3\nspace dimension: 3\n"
      << "sizes: " << h.dims[0] << " " << h.dims[1] << " " << h.dims[2] << "\n"
      << "space directions: (" << h.spacing[0] << ",0,0) (0," << h.spacing[1] << ",0) (0,0,"
      << h.spacing[2] << ")\n"
      << "space origin: (" << h.origin[0] << "," << h.origin[1] << "," << h.origin[2] << ")\n"
      << "kinds: domain domain domain\nendian: little\nencoding: raw\n";
  if (dataFile.empty())
    out << "\n";
  else
    out << "data file: " << dataFile << "\n";
  return out.str();
}

Status writeAll(int fd, const void* data, size_t bytes, const std::string& path) {
  const auto* p = static_cast<const uint8_t*>(data);
  while (bytes > 0) {
    const ssize_t n = ::write(fd, p, bytes);
    if (n < 0) {
      if (errno == EINTR) continue;
      return makeError(ErrorCode::kIo, path, ": write failed: ", std::strerror(errno));
    }
    p += n;
    bytes -= size_t(n);
  }
  return Status::ok();
}

}  // namespace

Result<DenseExportSummary> exportDenseNrrd(const VoxLinkFile& file, const std::string& path,
                                           double fill, const ProgressCallback& progress) {
  if (file.isScene())
    return makeError(ErrorCode::kUnsupported, file.path(),
                     ": dense export reads volume files (version 1); this is a scene (version 2)");
  const ScalarType type = file.sourceType();
  if (!nrrdTypeName(type))
    return makeError(ErrorCode::kUnsupported, file.path(), ": header: sourceType ", int(type),
                     " has no NRRD type");
  VOXLINK_RETURN_IF_ERROR(checkFill(type, fill, path));
  const FileHeader& h = file.header();
  const uint32_t n = file.brickSize();
  const size_t elem = scalarSize(type);
  const uint64_t sliceBytes = uint64_t{h.dims[0]} * h.dims[1] * elem;

  // A detached header (.nhdr) names a raw file beside it: both are written to temporaries and
  // renamed into place data first, so the header never points at a missing or partial file.
  const bool detached = hasExtension(path, ".nhdr");
  const std::string dataPath = detached ? path.substr(0, path.size() - 5) + ".raw" : path;
  const std::string dataName = std::filesystem::path(dataPath).filename().string();
  const std::string header = nrrdHeader(file, fill, detached ? dataName : "");
  if (detached) VOXLINK_RETURN_IF_ERROR(checkOutputTarget(dataPath, {file.path()}));
  VOXLINK_ASSIGN_OR_RETURN(TempFile temp, createTempBeside(dataPath, detached ? ".raw" : ".nrrd"));
  Status status = [&]() -> Status {
    if (!detached)
      VOXLINK_RETURN_IF_ERROR(writeAll(temp.fd, header.data(), header.size(), dataPath));
    // One brick layer of slices: the locator visits bricks z-layer by z-layer. The layer is
    // never deeper than the volume (a one-slice volume with 4-voxel bricks took 4 slices). A
    // valid file can be wide enough that it does not fit (65536^2 float64 voxels, 8-voxel
    // bricks: 256 GiB): refused before allocating, as filling it would touch every page.
    const uint32_t layerSlices = std::min(n, h.dims[2]);
    const uint64_t layerBytes = sliceBytes * layerSlices;
    auto tooLarge = [&] {
      return makeError(ErrorCode::kTooLarge, file.path(), ": a layer of bricks (", h.dims[0], " x ",
                       h.dims[1], " x ", layerSlices, " ", scalarName(type), " voxels, ",
                       layerBytes, " bytes) does not fit in memory for the dense export (",
                       memoryForThisProcess(), " bytes this process may use)");
    };
    if (layerBytes > memoryForThisProcess()) return tooLarge();
    std::vector<uint8_t> layer;
    try {
      layer.resize(layerBytes);
    } catch (const std::bad_alloc&) {
      return tooLarge();
    }
    std::vector<uint8_t> fillValue(elem);
    store(type, fill, fillValue.data());
    auto reset = [&] {
      for (size_t i = 0; i < layer.size(); i += elem)
        std::memcpy(&layer[i], fillValue.data(), elem);
    };
    reset();
    reportProgress(progress, 0, "exporting");
    uint32_t current = 0;  // brick layer held in `layer`
    Status writeStatus;
    auto flush = [&] {
      const uint32_t slices = std::min(n, h.dims[2] - current * n);
      if (writeStatus) writeStatus = writeAll(temp.fd, layer.data(), slices * sliceBytes, dataPath);
      reset();
      ++current;
      reportProgress(progress, double(current) / h.brickGrid[2], "exporting");
    };
    VoxelLocator(file).forEachVoxel([&](uint32_t x, uint32_t y, uint32_t z, uint64_t i) {
      while (z / n > current) flush();
      const uint64_t at = ((uint64_t{z % n} * h.dims[1] + y) * h.dims[0] + x) * elem;
      store(type, file.value(i), &layer[at]);
    });
    while (current < h.brickGrid[2]) flush();
    VOXLINK_RETURN_IF_ERROR(writeStatus);
    if (::close(temp.fd) != 0) {
      temp.fd = -1;
      return makeError(ErrorCode::kIo, path, ": close failed: ", std::strerror(errno));
    }
    temp.fd = -1;
    return Status::ok();
  }();
  if (!status) {
    if (temp.fd >= 0) ::close(temp.fd);
    discardTemp(temp.path);
    return status.error();
  }
  if (!detached) {
    VOXLINK_RETURN_IF_ERROR(commitTemp(temp.path, path));
  } else {
    VOXLINK_RETURN_IF_ERROR(commitTemp(temp.path, dataPath));
    const auto* text = reinterpret_cast<const uint8_t*>(header.data());
    if (Status s = writeWholeFile(path, {text, header.size()}); !s) {
      std::remove(dataPath.c_str());  // no data file without its header
      return s.error();
    }
  }
  DenseExportSummary summary;
  summary.keptVoxels = file.voxelCount();
  summary.filledVoxels = uint64_t{h.dims[0]} * h.dims[1] * h.dims[2] - summary.keptVoxels;
  summary.bytes = header.size() + sliceBytes * h.dims[2];
  return summary;
}

}  // namespace voxlink::report
