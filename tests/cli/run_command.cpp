// SPDX-License-Identifier: BSD-3-Clause
#include "tests/cli/run_command.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fstream>
#include <sstream>

#include "tests/support/test_util.h"

namespace voxlink::testing {
namespace {

// In a forked child: becomes the voxlink executable with `args` (exit 127 when it cannot).
[[noreturn]] void execVoxlink(const std::vector<std::string>& args) {
  std::vector<char*> argv;
  std::string exe = VOXLINK_EXECUTABLE;
  argv.push_back(exe.data());
  std::vector<std::string> copy = args;
  for (std::string& a : copy) argv.push_back(a.data());
  argv.push_back(nullptr);
  execv(exe.c_str(), argv.data());
  _exit(127);
}

}  // namespace

CommandResult runVoxlink(const std::vector<std::string>& args) { return runVoxlink(args, {}); }

CommandResult runVoxlink(const std::vector<std::string>& args, const RunOptions& options) {
  TempDir dir;
  const std::string outPath = options.stdoutPath.empty() ? dir.file("stdout") : options.stdoutPath;
  const std::string errPath = dir.file("stderr");
  CommandResult result;
  const pid_t pid = fork();
  if (pid == 0) {
    if (options.timeoutSeconds > 0) alarm(options.timeoutSeconds);
    if (options.fileSizeBytes > 0) {
      signal(SIGXFSZ, SIG_IGN);
      const rlimit limit{options.fileSizeBytes, options.fileSizeBytes};
      setrlimit(RLIMIT_FSIZE, &limit);
    }
    if (options.addressSpaceBytes > 0) {
      const rlimit limit{options.addressSpaceBytes, options.addressSpaceBytes};
      setrlimit(RLIMIT_AS, &limit);
    }
    // A given path (a device such as /dev/full) is opened as it is, never created: a missing
    // device must not become a regular file that later tests write to.
    const int out = options.stdoutPath.empty()
                        ? open(outPath.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644)
                        : open(outPath.c_str(), O_WRONLY);
    const int err = open(errPath.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    dup2(out, 1);
    dup2(err, 2);
    execVoxlink(args);
  }
  int status = 0;
  waitpid(pid, &status, 0);
  result.status = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  auto slurp = [](const std::string& p) {
    std::ifstream in(p);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
  };
  if (options.stdoutPath.empty()) result.out = slurp(outPath);
  result.err = slurp(errPath);
  return result;
}

int startVoxlink(const std::vector<std::string>& args) {
  const pid_t pid = fork();
  if (pid == 0) {
    const int null = open("/dev/null", O_WRONLY);
    dup2(null, 1);
    dup2(null, 2);
    execVoxlink(args);
  }
  return pid;
}

int waitVoxlink(int pid) {
  int status = 0;
  waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

}  // namespace voxlink::testing
