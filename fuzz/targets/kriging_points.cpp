// SPDX-License-Identifier: BSD-3-Clause
// Kriging sample tables (geostat): CSV with a header row, or GEO-EAS points, picked by
// content as `voxlink krige` does. Columns X, Y, V (Walker Lake's names), and Z when the first
// line names one.
#include <string_view>

#include "fuzz/fuzz_input.h"
#include "fuzz/fuzz_targets.h"
#include "geostat/point_set.h"

namespace voxlink::fuzz {

Status fuzzKrigingPoints(Input input) {
  const std::string path = scratch().write(splitFuzzFiles(input, "input.csv"));
  const std::string_view text(reinterpret_cast<const char*>(input.data()), input.size());
  const std::string_view firstLine = text.substr(0, text.find('\n'));
  const bool hasZ = firstLine.find('Z') != std::string_view::npos;
  const geostat::ColumnSelection columns{"X", "Y", hasZ ? "Z" : "", "V"};
  auto points = geostat::readPoints(path, columns);
  if (!points) return points.status();
  return Status::ok();
}

}  // namespace voxlink::fuzz
