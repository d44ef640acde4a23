// SPDX-License-Identifier: BSD-3-Clause
// `voxlink convert --batch LIST --out-dir DIR`: many conversions in one run, handed out one file
// at a time to whichever MPI rank is free (or done one after another by one process), one JSON
// line per file on stdout and a summary line at the end.
#pragma once

#include <functional>
#include <string>

#include "convert/converter.h"

namespace voxlink::cli {

using ConvertOneFile = std::function<Result<convert::ConvertSummary>(const std::string& input,
                                                                     const std::string& output)>;

// The exit status: 0 when every file was converted or skipped, 1 when any failed, the usual
// error status when the list itself is unusable.
int runBatch(const std::string& listPath, const std::string& outDir, bool resume,
             const ConvertOneFile& convertOne);

}  // namespace voxlink::cli
