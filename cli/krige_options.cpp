// SPDX-License-Identifier: BSD-3-Clause
#include "cli/krige_options.h"

#include <cmath>
#include <cstdlib>
#include <sstream>

namespace voxlink::cli {

Result<std::vector<double>> parseNumberList(const std::string& option, const std::string& text,
                                            size_t minCount, size_t maxCount) {
  std::vector<double> out;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) {
    char* end = nullptr;
    const double v = std::strtod(item.c_str(), &end);
    if (item.empty() || *end != '\0' || !std::isfinite(v))
      return makeError(ErrorCode::kInvalidArgument, option, " '", text, "': '", item,
                       "' is not a finite number");
    out.push_back(v);
  }
  if (out.size() < minCount || out.size() > maxCount)
    return makeError(ErrorCode::kInvalidArgument, option, " '", text, "': expected ", minCount,
                     minCount == maxCount ? "" : cat(" to ", maxCount),
                     " comma-separated numbers, got ", out.size());
  return out;
}

}  // namespace voxlink::cli
