// SPDX-License-Identifier: BSD-3-Clause
// One rank of a running `voxlink` job killed with SIGKILL (docs/scale.md, "Faults"): the rank is
// started through a shell that records its pid, killed at a chosen point of its work, and what
// must follow is checked: every rank (and every rank's helper process, base/temp_janitor.h)
// ends, mpirun exits with the signal's status and one line naming the rank and the signal,
// voxlink prints nothing of its own, and the output folder is left empty (no output, no
// temporary).
#pragma once

#include <sys/types.h>

#include <functional>
#include <string>

namespace voxlink::testing {

// When to kill: asked every few milliseconds, with the victim's pid, until it says yes.
using KillPoint = std::function<bool(pid_t victim)>;

// Once `folder` holds a file (rank 0's temporary for the output: the job is past its start) and
// `delayMs` more have passed.
KillPoint onceFolderHoldsFile(const std::string& folder, int delayMs);
// Once the victim has spent `cpuMs` of CPU time (user and system): past MPI's start-up (about
// 70 ms of CPU here), inside work that leaves no file before its end.
KillPoint onceCpuSpent(int cpuMs);

// Runs `voxlink ARGS` (`args`: shell words, as typed) on `ranks` ranks, kills rank `victim` at
// `when` and checks the above. `outDir` is the output's folder, named in `args` and holding
// nothing else; the job must still be at work when `when` says yes.
void expectKilledRankLeavesNothing(int ranks, int victim, const std::string& args,
                                   const std::string& outDir, const KillPoint& when);

}  // namespace voxlink::testing
