// SPDX-License-Identifier: BSD-3-Clause
// Writes a grid as a file the converter reads: raw data with a detached NRRD header (NAME.nhdr +
// NAME.raw) or a NumPy .npy (format 1.0, C order, shape (z, y, x)). Chosen by the output name's
// ending. Values are f64 or f32, little-endian. Nodes go to their places with positioned writes,
// so several processes (MPI ranks) can write one grid: one creates the temporary, the others
// attach() to it and close() it; the creator finish()es once every one has written.
#pragma once

#include <array>
#include <memory>
#include <string>
#include <vector>

#include "base/error.h"
#include "format/scalar_type.h"

namespace voxlink::geostat {

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
  // Another writer of the temporary `tempPath` that create() made for `path`; it never
  // removes the temporary (the creator does).
  static Result<std::unique_ptr<GridWriter>> attach(const std::string& path,
                                                    const std::string& tempPath,
                                                    const GridFileInfo& info);
  ~GridWriter();
  GridWriter(const GridWriter&) = delete;
  GridWriter& operator=(const GridWriter&) = delete;

  // Appends `count` slices (x fastest) converted to the file's type, after those appended.
  Status append(uint32_t count, const double* slices);
  // Writes nodes [firstNode, firstNode + nodes) of the grid (file order) at their place.
  Status write(uint64_t firstNode, uint64_t nodes, const double* values);
  uint64_t nodesWritten() const { return nodesWritten_; }
  const std::string& tempPath() const { return tempPath_; }
  // An attached writer's end: closes the file (checked).
  Status close();
  // The creator's end, once the writers together wrote `nodesWrittenByAll` nodes (every one):
  // the header, then the data and the header renamed into place.
  Status finish(uint64_t nodesWrittenByAll);
  Status finish() { return finish(nodesWritten_); }
  // The files finish() produced (the .nhdr and .raw, or the .npy).
  std::string dataPath() const { return dataPath_; }
  // The files a grid named `path` is written to: the .nhdr and its .raw, or the .npy.
  static std::vector<std::string> filesOf(const std::string& path);

 private:
  GridWriter() = default;
  std::string path_, dataPath_, tempPath_;
  GridFileInfo info_;
  int fd_ = -1;
  uint64_t dataOffset_ = 0;  // the .npy header's size, 0 for raw
  uint64_t nodesWritten_ = 0;
  bool nrrd_ = false;
  bool attached_ = false;
};

// The .npy header for a C-order little-endian array of `type` with shape (z, y, x), padded
// so the data starts at a multiple of 64 bytes.
std::string npyHeader(ScalarType type, std::array<uint32_t, 3> dims);

}  // namespace voxlink::geostat
