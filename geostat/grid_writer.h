// Writes a grid slab by slab as a file the converter reads: raw data with a detached NRRD
// header (NAME.nhdr + NAME.raw) or a NumPy .npy (format 1.0, C order, shape (z, y, x)).
// Chosen by the output name's ending. Values are f64 or f32, little-endian.
#pragma once

#include <array>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "format/error.h"
#include "format/scalar_type.h"

namespace voxlink::kriging {

struct GridFileInfo {
  std::array<uint32_t, 3> dims{1, 1, 1};
  std::array<double, 3> origin{0, 0, 0};
  std::array<double, 3> spacing{1, 1, 1};
  ScalarType type = ScalarType::kF64;  // kF64 or kF32
};

class GridWriter {
 public:
  // `path` ends in .nhdr or .npy. Data goes to a temporary name and is renamed by finish().
  static Result<std::unique_ptr<GridWriter>> create(const std::string& path,
                                                    const GridFileInfo& info);
  ~GridWriter();
  GridWriter(const GridWriter&) = delete;
  GridWriter& operator=(const GridWriter&) = delete;

  // Appends `count` slices (x fastest) converted to the file's type.
  Status append(uint32_t count, const double* slices);
  Status finish();
  // The files finish() produced (the .nhdr and .raw, or the .npy).
  std::string dataPath() const { return dataPath_; }
  // The files a grid named `path` is written to: the .nhdr and its .raw, or the .npy.
  static std::vector<std::string> filesOf(const std::string& path);

 private:
  GridWriter() = default;
  std::string path_, dataPath_, tempPath_;
  GridFileInfo info_;
  std::FILE* file_ = nullptr;
  uint64_t slicesWritten_ = 0;
  bool nrrd_ = false;
};

// The .npy header for a C-order little-endian array of `type` with shape (z, y, x), padded
// so the data starts at a multiple of 64 bytes.
std::string npyHeader(ScalarType type, std::array<uint32_t, 3> dims);

}  // namespace voxlink::kriging
