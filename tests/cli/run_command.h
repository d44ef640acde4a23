// Runs the `voxlink` executable as a user would and captures its exit status and output.
#pragma once

#include <string>
#include <vector>

namespace voxlink::testing {

struct CommandResult {
  int status = -1;  // exit status
  std::string out, err;
};

// Runs VOXLINK_EXECUTABLE with `args` (no shell involved).
CommandResult runVoxlink(const std::vector<std::string>& args);

}  // namespace voxlink::testing
