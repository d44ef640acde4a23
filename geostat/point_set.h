// SPDX-License-Identifier: BSD-3-Clause
// Scattered samples (2-D or 3-D coordinates with one value each) and the readers for the
// text tables they come in: CSV with a header row, and GEO-EAS / GSLIB point files.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "base/error.h"

namespace voxlink::geostat {

using Point3 = std::array<double, 3>;

struct PointSet {
  int dimension = 2;  // 2: z is 0 for every point
  std::vector<Point3> coords;
  std::vector<double> values;
  std::vector<double> drift;       // the external drift column, when one was selected
  std::vector<std::string> notes;  // rows skipped and why, for the command's summary

  size_t size() const { return values.size(); }
};

struct ColumnSelection {
  std::string x = "X";
  std::string y = "Y";
  std::string z;      // empty: 2-D data
  std::string value;  // required
  std::string drift;  // optional: an external drift column (rows missing it are skipped)
};

// Reads a CSV table with a header row. Names are matched case-insensitively and may be quoted.
// Rows whose value is NA, NaN or empty are skipped (counted in notes); a missing or non-numeric
// coordinate is an error naming the line and column.
Result<PointSet> readCsvPoints(const std::string& path, const ColumnSelection& columns);

// Reads a GEO-EAS point file (title line, variable count, one name per line, whitespace
// separated rows), as SGeMS and GSLIB write them. Values <= -1e21 or equal to SGeMS's
// no-data marker -9966699 are skipped.
Result<PointSet> readGeoEasPoints(const std::string& path, const ColumnSelection& columns);

// Picks the reader by content: a first line with a comma is CSV, anything else GEO-EAS.
Result<PointSet> readPoints(const std::string& path, const ColumnSelection& columns);

// readPoints in two steps, so that one process reads the file and others parse the same bytes
// (MPI ranks, docs/scale.md): the file's bytes (a regular file), then the points in `text`
// (errors name `path`).
Result<std::string> readSampleFile(const std::string& path);
Result<PointSet> parsePoints(const std::string& text, const std::string& path,
                             const ColumnSelection& columns);

}  // namespace voxlink::geostat
