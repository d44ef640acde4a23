// Finding and ordering the slices of one DICOM series in a folder (headers only, read with
// GDCM): slices sorted by position along the slice normal, geometry checked for consistency.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "format/error.h"
#include "format/scalar_type.h"
#include "sources/readers/axes.h"

namespace voxlink::convert {

struct DicomSlice {
  std::string path;
  Vec3 position{0, 0, 0};  // ImagePositionPatient
  double along = 0;        // position . slice normal
  int64_t instance = 0;    // InstanceNumber (0 when absent)
  double slope = 1;        // RescaleSlope
  double intercept = 0;    // RescaleIntercept
};

struct DicomSeries {
  std::vector<DicomSlice> slices;  // increasing `along`
  uint32_t rows = 0, columns = 0;
  ScalarType storedType = ScalarType::kU16;
  int bitsStored = 16;
  Vec3 rowDirection{1, 0, 0}, columnDirection{0, 1, 0}, normal{0, 0, 1};
  double rowSpacing = 1, columnSpacing = 1;  // PixelSpacing: between rows (y), between columns (x)
  double sliceSpacing = 1;
  std::vector<std::string> notes;
};

// Reads the headers of the DICOM files in `dir` (not recursive) and orders them.
// kSizeMismatch: files disagree on Rows/Columns/bits/PixelSpacing; kUnsupported: several series,
// color, multi-frame, oblique-varying orientation or non-uniform slice gaps; kCorrupt: a file
// GDCM cannot parse or two slices at one position. Messages name the file and the tag.
Result<DicomSeries> scanDicomSeries(const std::string& dir);

}  // namespace voxlink::convert
