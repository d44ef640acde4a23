// SPDX-License-Identifier: BSD-3-Clause
// A dense source volume read slice by slice (z slices, x fastest), so a converter never needs
// the whole volume in memory. Readers for each file format implement this interface.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "base/error.h"
#include "format/scalar_type.h"

namespace voxlink::sources {

// How a reader mapped stored numbers to the values it serves (DICOM RescaleSlope/Intercept,
// DoseGridScaling): value = stored * slope + intercept, slope and intercept per slice within
// the ranges. The converter records it in the file's META; `voxlink info` reports it.
struct SourceRescale {
  std::string field;       // "RescaleSlope/RescaleIntercept", "DoseGridScaling"
  std::string storedType;  // the file's own type, e.g. "u32"
  double minSlope = 1, maxSlope = 1, minIntercept = 0, maxIntercept = 0;
};

struct VolumeInfo {
  std::array<uint32_t, 3> dims{0, 0, 0};
  ScalarType type = ScalarType::kU8;
  std::array<double, 3> spacing{1.0, 1.0, 1.0};
  std::array<double, 3> origin{0.0, 0.0, 0.0};  // world position of voxel (0,0,0)'s centre
  std::string path;                             // as the user gave it
  std::string format;  // "raw", "nrrd", "metaimage", "nifti", "dicom", "image-stack", "vdb", ...
  // Things the reader did or ignored that a user should know ("z order reversed to increasing
  // slice position", "oblique space directions: only their lengths are used as spacing").
  std::vector<std::string> notes;
  std::optional<SourceRescale> rescale;  // set by readers that rescale and record it
  // Every file the source reads: the header, the data files it names, a DICOM series' or an
  // image stack's files. Commands refuse to write their output over any of them.
  std::vector<std::string> files;

  uint64_t sliceVoxels() const { return uint64_t{dims[0]} * dims[1]; }
  uint64_t voxelCount() const { return sliceVoxels() * dims[2]; }
  uint64_t sliceBytes() const { return sliceVoxels() * scalarSize(type); }
};

class VolumeSource {
 public:
  virtual ~VolumeSource() = default;
  const VolumeInfo& info() const { return info_; }
  // Adds `path` to info().files unless it is there already or is no regular file.
  void recordFileRead(const std::string& path);

  // Copies slices [z0, z0 + count) into dst as native-endian values of info().type.
  // Sequential sources (compressed streams) need z0 >= the end of the previous read;
  // call rewind() to start over. Random-access sources accept any order.
  virtual Status read(uint32_t z0, uint32_t count, void* dst) = 0;
  virtual Status rewind() { return Status::ok(); }
  virtual bool randomAccess() const { return false; }

  // Sources whose voxels may hold no data (OpenVDB's inactive voxels, read as the background)
  // say so here; a converter never keeps such a voxel, whatever the classification.
  virtual bool hasInactiveVoxels() const { return false; }
  // Copies the active flags (1 holds data, 0 does not) of slices [z0, z0 + count) into dst, one
  // byte per voxel in read()'s order. The default says every voxel is active.
  virtual Status readActive(uint32_t z0, uint32_t count, uint8_t* dst);
  // read() and readActive() together; sources override it to do both in one pass.
  virtual Status readWithActive(uint32_t z0, uint32_t count, void* dst, uint8_t* active) {
    VOXLINK_RETURN_IF_ERROR(read(z0, count, dst));
    return readActive(z0, count, active);
  }

  // Zero-copy path: a pointer to slices [z0, z0 + count) already in memory in native layout
  // (a mapped raw file), valid while the source lives; nullptr when the source cannot.
  virtual const void* map(uint32_t /*z0*/, uint32_t /*count*/) { return nullptr; }
  // Says mapped slices are done with, so their pages leave the resident set.
  virtual void unmap(uint32_t /*z0*/, uint32_t /*count*/) {}

 protected:
  // kInvalidArgument unless slices [z0, z0 + count) lie inside the volume.
  Status checkSliceRange(uint32_t z0, uint32_t count) const;

  VolumeInfo info_;
};

enum class Endian { kLittle, kBig };

// What the command line may say about an input. Raw files need dims and type; for other
// formats a given value must agree with the header or the open fails.
struct OpenOptions {
  std::optional<std::array<uint32_t, 3>> dims;
  std::optional<ScalarType> type;
  Endian endian = Endian::kLittle;
  uint64_t headerBytes = 0;                      // raw: bytes to skip before the data
  std::optional<std::array<double, 3>> spacing;  // overrides the file's spacing
  std::string format;       // force a reader ("raw", "nrrd", ...) instead of guessing
  std::string vdbGrid;      // .vdb: the grid to read (default: the first float grid)
  std::string variable;     // multi-variable inputs (GSLIB/GEO-EAS): which column to read
  std::string dicomSeries;  // DICOM folders: SeriesInstanceUID or 1-based index to read
};

// Opens `path` with the reader its name or content calls for.
Result<std::unique_ptr<VolumeSource>> openVolume(const std::string& path,
                                                 const OpenOptions& options = {});

// Names of the readers openVolume() knows, for --help and error messages.
std::vector<std::string> readerNames();

// Reads the whole volume into memory (tests, small inputs, the reference renderer).
Result<std::vector<uint8_t>> readAll(VolumeSource& source);

}  // namespace voxlink::sources
