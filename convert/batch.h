// SPDX-License-Identifier: BSD-3-Clause
// A batch of conversions (`voxlink convert --batch LIST --out-dir DIR`): the list's inputs, the
// output each becomes, and the order they are handed out in (largest first, so that a large
// file taken last does not keep one rank busy while the others wait).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "base/error.h"

namespace voxlink::convert {

struct BatchItem {
  std::string input;   // as resolved: relative entries are taken from the list's folder
  std::string output;  // DIR/<name without extension>.vxl
  uint64_t bytes = 0;  // input size (a folder: the sum of its files), for ordering
  uint64_t line = 0;   // in the list, from 1
};

// One input per line; blank lines and lines starting with '#' are skipped. Fails naming the list
// and line for an input that does not exist, or two inputs that would write one output.
// Items come largest first (ties in list order).
Result<std::vector<BatchItem>> readBatchList(const std::string& listPath,
                                             const std::string& outDir);

// The output name for an input: its file name without the extension (".nii.gz" counts as one),
// plus ".vxl".
std::string batchOutputName(const std::string& input);

}  // namespace voxlink::convert
