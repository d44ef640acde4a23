// SPDX-License-Identifier: BSD-3-Clause
// Debian's GDCM is built with assertions on: some damaged files (cut inside the header, for
// one) make it abort the whole process instead of returning false. Before the converter reads a
// series in-process, a child process reads every file with the same GDCM calls; if the child
// dies, the damaged file is named in an error and the series is never read here.
#pragma once

#include <string>
#include <vector>

#include "base/error.h"

namespace voxlink::sources {

// kCorrupt naming the file GDCM died on; Ok when GDCM reads every file without dying (it may
// still refuse some: the caller's own reads report that with their reasons).
Status checkGdcmSurvives(const std::vector<std::string>& files);

}  // namespace voxlink::sources
