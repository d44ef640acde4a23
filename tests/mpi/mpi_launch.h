// SPDX-License-Identifier: BSD-3-Clause
// Runs `voxlink` under mpirun (Open MPI, quiet, oversubscribed: this machine may have fewer cores
// than ranks; as root when the tests run as root) and without it, capturing status and output.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace voxlink::testing {

struct Launch {
  int status = -1;  // exit status of mpirun (or of voxlink), 128 + signal if killed
  std::string out, err;
};

// voxlink ARGS, no launcher.
Launch runPlain(const std::vector<std::string>& args);
// mpirun -n RANKS voxlink ARGS.
Launch runRanks(int ranks, const std::vector<std::string>& args);
// mpirun with a command line of its own after the launcher's options (MPMD `A : B` forms);
// "VOXLINK" in it stands for the executable. Runs through /bin/sh.
// quiet = false: without -q, so that mpirun reports a rank that died of a signal.
Launch runLauncher(const std::string& tail, bool quiet = true);

// The launcher's options used by the calls above.
std::string launcherPrefix(bool quiet = true);

// Lines in `text` (newlines counted).
size_t lineCount(const std::string& text);

// A fault's report: stderr is one line, from rank `rank`, naming `cause`.
void expectOneLineFromRank(const Launch& r, int rank, const std::string& cause);

}  // namespace voxlink::testing
