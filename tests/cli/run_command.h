// SPDX-License-Identifier: BSD-3-Clause
// Runs the `voxlink` executable as a user would and captures its exit status and output.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace voxlink::testing {

struct CommandResult {
  int status = -1;  // exit status
  std::string out, err;
};

// Runs VOXLINK_EXECUTABLE with `args` (no shell involved).
CommandResult runVoxlink(const std::vector<std::string>& args);

struct RunOptions {
  std::string stdoutPath;       // where stdout goes (e.g. /dev/full); empty: captured
  unsigned timeoutSeconds = 0;  // SIGALRM after this many seconds (a hang fails, not blocks)
  // The command's RLIMIT_AS (`ulimit -v`); 0: unchanged. Not under AddressSanitizer, which
  // reserves terabytes of shadow memory at start: see addressSpaceLimitsWork().
  uint64_t addressSpaceBytes = 0;
  // The command's RLIMIT_FSIZE, SIGXFSZ ignored: writes past it fail with EFBIG, as on a full
  // disk. 0: unchanged.
  uint64_t fileSizeBytes = 0;
};
CommandResult runVoxlink(const std::vector<std::string>& args, const RunOptions& options);

// False in a build with AddressSanitizer (the executable is built like the tests): it cannot
// start within an address-space limit, so tests that set one skip there.
constexpr bool addressSpaceLimitsWork() {
#if defined(__SANITIZE_ADDRESS__)
  return false;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
  return false;
#else
  return true;
#endif
#else
  return true;
#endif
}

// Starts VOXLINK_EXECUTABLE in the background (stdout and stderr to /dev/null); returns its pid.
int startVoxlink(const std::vector<std::string>& args);
// Waits for a started command; its exit status, or 128 + the signal that ended it.
int waitVoxlink(int pid);

}  // namespace voxlink::testing
