// SPDX-License-Identifier: BSD-3-Clause
// Option parsing shared by `voxlink krige` and `voxlink grf`: comma lists and variogram models.
#pragma once

#include <string>
#include <vector>

#include "base/error.h"

namespace voxlink::cli {

// "1,2,3" -> {1, 2, 3}; between minCount and maxCount finite numbers.
Result<std::vector<double>> parseNumberList(const std::string& option, const std::string& text,
                                            size_t minCount, size_t maxCount);

}  // namespace voxlink::cli
