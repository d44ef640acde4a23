// SPDX-License-Identifier: BSD-3-Clause
#include "geostat/point_set.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "base/regular_file.h"

namespace voxlink::geostat {
namespace {

constexpr double kSgemsNoData = -9966699.0;
// Coordinates beyond this make squared distances overflow: (2 x 1e150)^2 x 3 axes is 1.2e301,
// still finite. Near 1e308 the bounding box's diagonal was inf ("merged ... closer than inf")
// and predictions were not finite.
constexpr double kMaxCoordinate = 1e150;

std::string trim(const std::string& s) {
  size_t b = 0, e = s.size();
  while (b < e && std::isspace(static_cast<unsigned char>(s[b]))) ++b;
  while (e > b && std::isspace(static_cast<unsigned char>(s[e - 1]))) --e;
  std::string t = s.substr(b, e - b);
  if (t.size() >= 2 && (t.front() == '"' || t.front() == '\'') && t.back() == t.front())
    t = t.substr(1, t.size() - 2);
  return t;
}

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

bool isMissing(const std::string& field) {
  const std::string f = lower(field);
  return f.empty() || f == "na" || f == "nan";
}

bool parseNumber(const std::string& field, double& out) {
  if (field.empty()) return false;
  char* end = nullptr;
  out = std::strtod(field.c_str(), &end);
  return *end == '\0' && std::isfinite(out);
}

// Indices of the selected columns in `names`; z is -1 for 2-D data.
Result<std::array<int, 5>> findColumns(const std::string& path,
                                       const std::vector<std::string>& names,
                                       const ColumnSelection& columns) {
  if (columns.value.empty())
    return makeError(
        ErrorCode::kInvalidArgument, path, ": no value column selected (one of: ",
        [&] {
          std::string all;
          for (const auto& n : names) all += (all.empty() ? "" : ", ") + n;
          return all;
        }(),
        ")");
  std::array<int, 5> index{-1, -1, -1, -1, -1};
  const std::string wanted[5] = {columns.x, columns.y, columns.z, columns.value, columns.drift};
  const char* role[5] = {"x", "y", "z", "value", "external drift"};
  for (int r = 0; r < 5; ++r) {
    if (wanted[r].empty()) continue;
    for (size_t i = 0; i < names.size(); ++i)
      if (lower(names[i]) == lower(wanted[r])) index[r] = static_cast<int>(i);
    if (index[r] < 0) {
      std::string all;
      for (const auto& n : names) all += (all.empty() ? "" : ", ") + n;
      return makeError(ErrorCode::kInvalidArgument, path, ": ", role[r], " column '", wanted[r],
                       "' not found (columns: ", all, ")");
    }
  }
  return index;
}

// Adds one row's fields; returns an error for bad coordinates, skips missing values.
Status addRow(const std::string& path, size_t line, const std::vector<std::string>& fields,
              const std::array<int, 5>& col, const std::vector<std::string>& names, bool geoEas,
              PointSet& out, size_t& skipped) {
  // Every row holds every column (an empty field is a missing value): a row with a field too
  // many or too few has its columns shifted, and was read as long as the used ones were there.
  if (fields.size() != names.size())
    return makeError(fields.size() < names.size() ? ErrorCode::kTruncated : ErrorCode::kCorrupt,
                     path, ": line ", line, ": ", fields.size(), " fields, expected ",
                     names.size());
  double v = 0;
  const std::string& valueField = fields[col[3]];
  if (isMissing(valueField) ||
      (parseNumber(valueField, v) && geoEas && (v == kSgemsNoData || v <= -1e21))) {
    ++skipped;
    return Status::ok();
  }
  if (!parseNumber(valueField, v))
    return makeError(ErrorCode::kInvalidArgument, path, ": line ", line, ": column '",
                     names[col[3]], "': '", valueField, "' is not a number");
  Point3 p{0, 0, 0};
  for (int a = 0; a < 3; ++a) {
    if (col[a] < 0) continue;
    if (!parseNumber(fields[col[a]], p[a]))
      return makeError(ErrorCode::kInvalidArgument, path, ": line ", line, ": coordinate column '",
                       names[col[a]], "': '", fields[col[a]], "' is not a finite number");
    if (std::abs(p[a]) > kMaxCoordinate)
      return makeError(ErrorCode::kInvalidArgument, path, ": line ", line, ": coordinate column '",
                       names[col[a]], "': ", fields[col[a]], " is outside [-1e150, 1e150]",
                       " (distances between samples would overflow)");
  }
  double drift = 0;
  if (col[4] >= 0) {
    const std::string& field = fields[col[4]];
    // A sample without its drift value cannot enter the drift's system: skipped like one
    // without a value.
    if (isMissing(field) ||
        (parseNumber(field, drift) && geoEas && (drift == kSgemsNoData || drift <= -1e21))) {
      ++skipped;
      return Status::ok();
    }
    if (!parseNumber(field, drift))
      return makeError(ErrorCode::kInvalidArgument, path, ": line ", line,
                       ": external drift column '", names[col[4]], "': '", field,
                       "' is not a finite number");
    out.drift.push_back(drift);
  }
  out.coords.push_back(p);
  out.values.push_back(v);
  return Status::ok();
}

std::vector<std::string> splitCsv(const std::string& line) {
  std::vector<std::string> fields;
  std::string field;
  bool quoted = false;
  for (char c : line) {
    if (c == '"')
      quoted = !quoted;
    else if (c == ',' && !quoted) {
      fields.push_back(trim(field));
      field.clear();
    } else if (c != '\r')
      field += c;
  }
  fields.push_back(trim(field));
  return fields;
}

std::vector<std::string> splitWhitespace(const std::string& line) {
  std::istringstream in(line);
  std::vector<std::string> fields;
  std::string f;
  while (in >> f) fields.push_back(f);
  return fields;
}

void finish(PointSet& set, const ColumnSelection& columns, size_t skipped,
            const std::string& path) {
  set.dimension = columns.z.empty() ? 2 : 3;
  if (skipped > 0)
    set.notes.push_back(
        cat(path, ": ", skipped,
            columns.drift.empty()
                ? " rows with a missing value (NA/NaN/no-data) skipped"
                : " rows with a missing value or external drift (NA/NaN/no-data) skipped"));
}

Result<PointSet> csvPoints(std::istream& in, const std::string& path,
                           const ColumnSelection& columns) {
  std::string line;
  if (!std::getline(in, line))
    return makeError(ErrorCode::kTruncated, path, ": empty file, expected a header row");
  const std::vector<std::string> names = splitCsv(line);
  VOXLINK_ASSIGN_OR_RETURN(const auto col, findColumns(path, names, columns));
  PointSet set;
  size_t lineNo = 1, skipped = 0;
  while (std::getline(in, line)) {
    ++lineNo;
    if (trim(line).empty()) continue;
    VOXLINK_RETURN_IF_ERROR(addRow(path, lineNo, splitCsv(line), col, names, false, set, skipped));
  }
  finish(set, columns, skipped, path);
  return set;
}

Result<PointSet> geoEasPoints(std::istream& in, const std::string& path,
                              const ColumnSelection& columns) {
  std::string title, countLine;
  if (!std::getline(in, title) || !std::getline(in, countLine))
    return makeError(ErrorCode::kTruncated, path,
                     ": GEO-EAS header: expected a title line and a variable count");
  // strtol's end pointer points into this string, so it must outlive the check.
  const std::string countText = trim(countLine);
  char* end = nullptr;
  const long count = std::strtol(countText.c_str(), &end, 10);
  if (*end != '\0' || count < 1 || count > 10000)
    return makeError(
        ErrorCode::kInvalidArgument, path,
        ": GEO-EAS header: line 2 'number of variables': expected an integer in 1..10000, got '",
        countText, "'");
  std::vector<std::string> names;
  std::string line;
  for (long i = 0; i < count; ++i) {
    if (!std::getline(in, line))
      return makeError(ErrorCode::kTruncated, path, ": GEO-EAS header: ", count,
                       " variable names announced, file ends after ", i);
    names.push_back(trim(line));
  }
  VOXLINK_ASSIGN_OR_RETURN(const auto col, findColumns(path, names, columns));
  PointSet set;
  size_t lineNo = 2 + static_cast<size_t>(count), skipped = 0;
  while (std::getline(in, line)) {
    ++lineNo;
    const auto fields = splitWhitespace(line);
    if (fields.empty()) continue;
    VOXLINK_RETURN_IF_ERROR(addRow(path, lineNo, fields, col, names, true, set, skipped));
  }
  finish(set, columns, skipped, path);
  return set;
}

}  // namespace

Result<PointSet> readCsvPoints(const std::string& path, const ColumnSelection& columns) {
  std::ifstream in(path);
  if (!in) return makeError(ErrorCode::kIo, path, ": cannot open");
  return csvPoints(in, path, columns);
}

Result<PointSet> readGeoEasPoints(const std::string& path, const ColumnSelection& columns) {
  std::ifstream in(path);
  if (!in) return makeError(ErrorCode::kIo, path, ": cannot open");
  return geoEasPoints(in, path, columns);
}

Result<std::string> readSampleFile(const std::string& path) {
  VOXLINK_RETURN_IF_ERROR(base::requireRegularFile(path, "sample file"));  // a FIFO would block
  std::ifstream in(path, std::ios::binary);
  if (!in) return makeError(ErrorCode::kIo, path, ": cannot open");
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) return makeError(ErrorCode::kIo, path, ": read failed");
  return text.str();
}

Result<PointSet> parsePoints(const std::string& text, const std::string& path,
                             const ColumnSelection& columns) {
  std::istringstream in(text);
  const std::string first = text.substr(0, text.find('\n'));
  if (first.find(',') != std::string::npos) return csvPoints(in, path, columns);
  return geoEasPoints(in, path, columns);
}

Result<PointSet> readPoints(const std::string& path, const ColumnSelection& columns) {
  VOXLINK_ASSIGN_OR_RETURN(const std::string text, readSampleFile(path));
  return parsePoints(text, path, columns);
}

}  // namespace voxlink::geostat
