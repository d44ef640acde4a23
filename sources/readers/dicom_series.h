// SPDX-License-Identifier: BSD-3-Clause
// Finding the DICOM series under a folder (recursive; headers only, read with GDCM), listing
// them, and ordering the slices of one: single-frame files and the frames of multi-frame files
// sorted by position along the slice normal, geometry checked for consistency.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "base/error.h"
#include "format/scalar_type.h"
#include "sources/readers/detail/dicom_header.h"

namespace voxlink::sources {

struct DicomSeries {
  std::vector<DicomSlice> slices;  // increasing `along`
  uint32_t rows = 0, columns = 0;
  ScalarType storedType = ScalarType::kU16;
  int bitsStored = 16;
  Vec3 rowDirection{1, 0, 0}, columnDirection{0, 1, 0}, normal{0, 0, 1};
  double rowSpacing = 1, columnSpacing = 1;  // PixelSpacing: between rows (y), between columns (x)
  double sliceSpacing = 1;
  Vec3 origin{0, 0, 0};
  std::string rescaleField;  // "RescaleSlope/RescaleIntercept", "DoseGridScaling" or empty
  std::vector<std::string> notes;
};

// One series found under a folder, for `voxlink dicom list`.
struct DicomSeriesSummary {
  std::string uid, modality, description;
  uint64_t files = 0, frames = 0, bytes = 0;  // bytes: the files' sizes
  std::array<uint32_t, 3> dims{0, 0, 0};      // valid when `problem` is empty
  std::array<double, 3> spacing{0, 0, 0};
  std::string problem;  // why the series cannot be read as a volume, else empty
};

struct DicomFolderListing {
  std::vector<DicomSeriesSummary> series;  // in the order of their first file (natural sort)
  uint64_t otherFiles = 0;                 // files that are not DICOM (and DICOMDIR)
  uint64_t nonImages = 0;                  // DICOM files without pixel data (reports, RT plans)
};

// Every series under `path` (a folder, searched recursively, or one file).
Result<DicomFolderListing> listDicomSeries(const std::string& path);

// The slices of one series under `path` (a folder, searched recursively, or one file).
// `choice` picks a series by SeriesInstanceUID or by its 1-based index in listDicomSeries()'s
// order; empty: the only series (kUnsupported listing them when there are several).
// kSizeMismatch: files disagree on Rows/Columns/bits/PixelSpacing; kUnsupported: color, mixed
// orientations, non-uniform slice gaps, gantry tilt; kCorrupt: a file GDCM cannot parse or two
// slices at one position. Messages name the file (and frame) and the tag.
Result<DicomSeries> scanDicomSeries(const std::string& path, const std::string& choice = {});

}  // namespace voxlink::sources
