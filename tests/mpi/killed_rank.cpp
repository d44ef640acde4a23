// SPDX-License-Identifier: BSD-3-Clause
#include "tests/mpi/killed_rank.h"

#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>
#include <vector>

#include "tests/mpi/mpi_launch.h"
#include "tests/support/test_util.h"

namespace voxlink::testing {
namespace {

namespace fs = std::filesystem;
using std::chrono::milliseconds;
using Clock = std::chrono::steady_clock;

// Lines of `text` that hold every one of `parts`.
size_t linesHoldingAll(const std::string& text, const std::vector<std::string>& parts) {
  std::istringstream lines(text);
  size_t count = 0;
  for (std::string line; std::getline(lines, line);) {
    bool all = true;
    for (const std::string& part : parts) all = all && line.find(part) != std::string::npos;
    count += all;
  }
  return count;
}

// Processes whose command line names `text` (the job's ranks and their helpers name the output
// folder; the launcher and its shell are gone once runLauncher returns).
std::vector<std::string> processesNaming(const std::string& text) {
  std::vector<std::string> found;
  std::error_code ec;
  for (const fs::directory_entry& entry : fs::directory_iterator("/proc", ec)) {
    const std::string pid = entry.path().filename();
    if (pid.find_first_not_of("0123456789") != std::string::npos) continue;
    std::ifstream in(entry.path() / "cmdline");
    std::string line((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    for (char& c : line)
      if (c == '\0') c = ' ';
    if (line.find(text) != std::string::npos) found.push_back(pid + ": " + line);
  }
  return found;
}

// User plus system time of process `pid` in milliseconds, -1 when it is gone.
long cpuMilliseconds(pid_t pid) {
  std::ifstream in("/proc/" + std::to_string(pid) + "/stat");
  std::string stat((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const size_t name = stat.rfind(')');  // the command name may hold spaces
  if (name == std::string::npos) return -1;
  std::istringstream fields(stat.substr(name + 2));
  std::string skip;
  for (int field = 3; field < 14; ++field) fields >> skip;  // state .. cmajflt
  long user = 0, system = 0;
  if (!(fields >> user >> system)) return -1;
  return (user + system) * 1000 / sysconf(_SC_CLK_TCK);
}

}  // namespace

KillPoint onceFolderHoldsFile(const std::string& folder, int delayMs) {
  auto seenAt = std::make_shared<Clock::time_point>();
  return [folder, delayMs, seenAt](pid_t) {
    if (*seenAt == Clock::time_point()) {
      if (listDir(folder).empty()) return false;
      *seenAt = Clock::now();
    }
    return Clock::now() - *seenAt >= milliseconds(delayMs);
  };
}

KillPoint onceCpuSpent(int cpuMs) {
  return [cpuMs](pid_t victim) { return cpuMilliseconds(victim) >= cpuMs; };
}

void expectKilledRankLeavesNothing(int ranks, int victim, const std::string& args,
                                   const std::string& outDir, const KillPoint& when) {
  TempDir scratch;
  const std::string pidFile = scratch.file("victim.pid");
  const std::string victimApp =
      "-n 1 sh -c \"echo \\$\\$ > " + pidFile + "; exec \\$0 " + args + "\" VOXLINK";
  const std::string plainApp = "-n 1 VOXLINK " + args;
  std::string apps;
  for (int rank = 0; rank < ranks; ++rank)
    apps += (rank ? " : " : "") + (rank == victim ? victimApp : plainApp);
  Launch r;
  std::atomic<bool> ended{false};
  // Without -q: mpirun's line is the report of a rank that cannot report itself.
  std::thread launch([&] {
    r = runLauncher(apps, false);
    ended = true;
  });
  pid_t pid = 0;
  bool killed = false;
  while (!ended && !killed) {
    if (pid == 0) std::ifstream(pidFile) >> pid;  // 0 until the shell has written it
    if (pid != 0 && when(pid)) killed = kill(pid, SIGKILL) == 0;
    std::this_thread::sleep_for(milliseconds(2));
  }
  launch.join();
  ASSERT_TRUE(killed) << "the job ended before rank " << victim << " was killed:\n" << r.err;
  EXPECT_EQ(r.status, 128 + SIGKILL) << r.err;
  const std::string rankWord = "process rank " + std::to_string(victim) + " with PID";
  EXPECT_EQ(linesHoldingAll(r.err, {rankWord, "exited on signal 9 (Killed)"}), 1u) << r.err;
  EXPECT_EQ(r.err.find("voxlink: "), std::string::npos) << r.err;  // no rank reports a cause
  // A rank's helper removes the temporaries once its rank is gone, and then ends itself.
  std::vector<std::string> left = listDir(outDir), alive = processesNaming(outDir);
  for (int i = 0; i < 300 && !(left.empty() && alive.empty()); ++i) {
    std::this_thread::sleep_for(milliseconds(10));
    left = listDir(outDir);
    alive = processesNaming(outDir);
  }
  EXPECT_TRUE(left.empty()) << left.front();
  EXPECT_TRUE(alive.empty()) << alive.front();
}

}  // namespace voxlink::testing
