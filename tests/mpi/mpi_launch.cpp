// SPDX-License-Identifier: BSD-3-Clause
#include "tests/mpi/mpi_launch.h"

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "tests/support/test_util.h"

namespace voxlink::testing {
namespace {

std::string quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) {
    if (c == '\'')
      q += "'\\''";
    else
      q += c;
  }
  q += '\'';
  return q;
}

std::string readText(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

Launch runShell(const std::string& command) {
  TempDir capture;
  const std::string line = command + " >" + capture.file("out") + " 2>" + capture.file("err");
  const int raw = std::system(line.c_str());
  Launch r;
  r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : 128 + WTERMSIG(raw);
  r.out = readText(capture.file("out"));
  r.err = readText(capture.file("err"));
  return r;
}

std::string joined(const std::vector<std::string>& args) {
  std::string s = quote(VOXLINK_EXECUTABLE);
  for (const std::string& a : args) {
    s += ' ';
    s += quote(a);
  }
  return s;
}

}  // namespace

std::string launcherPrefix(bool quiet) {
  // -q: without it Open MPI adds its own notice of a rank's non-zero exit to voxlink's line.
  std::string prefix = quote(VOXLINK_MPIEXEC) + (quiet ? " -q" : "") + " --oversubscribe";
  if (geteuid() == 0) prefix += " --allow-run-as-root";
  return prefix;
}

Launch runPlain(const std::vector<std::string>& args) { return runShell(joined(args)); }

Launch runRanks(int ranks, const std::vector<std::string>& args) {
  return runShell(launcherPrefix() + " -n " + std::to_string(ranks) + " " + joined(args));
}

Launch runLauncher(const std::string& tail, bool quiet) {
  std::string expanded = tail;
  for (size_t at; (at = expanded.find("VOXLINK")) != std::string::npos;)
    expanded.replace(at, 7, quote(VOXLINK_EXECUTABLE));
  return runShell(launcherPrefix(quiet) + " " + expanded);
}

size_t lineCount(const std::string& text) {
  return static_cast<size_t>(std::count(text.begin(), text.end(), '\n'));
}

void expectOneLineFromRank(const Launch& r, int rank, const std::string& cause) {
  EXPECT_EQ(lineCount(r.err), 1u) << r.err;
  EXPECT_EQ(r.err.rfind("voxlink: rank " + std::to_string(rank) + ": ", 0), 0u) << r.err;
  EXPECT_NE(r.err.find(cause), std::string::npos) << r.err;
}

}  // namespace voxlink::testing
