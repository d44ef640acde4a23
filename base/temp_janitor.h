// SPDX-License-Identifier: BSD-3-Clause
// A helper process that removes this process's registered temporaries when this process ends
// in a way its own handlers cannot see: SIGKILL, or Open MPI ending a rank with _exit() when
// another rank died (docs/scale.md, "Faults"). Temporaries registered for cleanup
// (base/output_file.h) are also told to it; when this process is gone (its socket closes), it
// removes those still registered and exits.
#pragma once

#include <string>

namespace voxlink {
inline namespace base {

// Forks the helper; call before any thread starts (before MPI_Init). False if it could not.
bool startTempJanitor();

// Used by registerTempForCleanup / unregisterTempForCleanup: '+' adds `path`, '-' removes it.
void tellTempJanitor(char op, const std::string& path);

}  // namespace base
}  // namespace voxlink
