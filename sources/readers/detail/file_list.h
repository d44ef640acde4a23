// SPDX-License-Identifier: BSD-3-Clause
// Lists of data files named by a header: the numbered form "quarter.%d 1 93 1" (NRRD
// `data file:`, MetaImage `ElementDataFile`) and natural (number-aware) ordering of file names
// for image stacks.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "base/error.h"

namespace voxlink::sources {

// Expands "<format> <min> <max> <step>" where <format> holds exactly one integer conversion
// (%d, %i, %u, with optional 0 flag and width, e.g. %03d; "%%" is a literal %). The step may be
// negative. The format is parsed here, never handed to printf.
Result<std::vector<std::string>> expandNumberedFiles(const std::vector<std::string>& words,
                                                     const std::string& file,
                                                     std::string_view field);

// expandNumberedFiles of header `headerPath`, each name placed beside the header (besideHeader)
// and appended to `paths`.
Status appendNumberedFiles(const std::vector<std::string>& words, const std::string& headerPath,
                           std::string_view field, std::vector<std::string>& paths);

// `name` relative to the directory of `headerPath`, unless it is absolute.
std::string besideHeader(const std::string& headerPath, const std::string& name);

// "slice2.png" < "slice10.png": digit runs compare by value, the rest byte by byte.
bool naturalLess(std::string_view a, std::string_view b);

}  // namespace voxlink::sources
