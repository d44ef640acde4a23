// Safe creation of output files: every command writes to a temporary file beside the target
// and renames it into place. The temporary has a short unique name made with O_EXCL (so a
// symlink planted at a predictable name is never written through, and a 255-byte target name
// still fits), is removed if the process is stopped by SIGINT, SIGTERM or SIGHUP, and the target
// is checked first: it must not be the input, nor an existing non-regular file (/dev/null, a
// directory, a FIFO) that a rename would replace.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "format/error.h"

namespace voxlink::format {

// kInvalidArgument when `target` exists and is not a regular file, or is the same file (device
// and inode) as one of `inputs`.
Status checkOutputTarget(const std::string& target, const std::vector<std::string>& inputs = {});

// An open, empty temporary file in the target's directory: "<dir>/.vl-XXXXXX<suffix>", mode
// 0644, registered for removal on signals. The caller owns fd and path.
struct TempFile {
  int fd = -1;
  std::string path;
};
Result<TempFile> createTempBeside(const std::string& target, std::string_view suffix = "");

// Renames a finished temporary over `target` and forgets it for signal cleanup; on failure the
// temporary is removed.
Status commitTemp(const std::string& tempPath, const std::string& target);

// Removes a temporary (after a failure) and forgets it.
void discardTemp(const std::string& tempPath);

// Temporaries registered here are unlinked by the handlers installed below (async-signal-safe:
// fixed slots, no allocation in the handler). At most 32 at a time; more are not tracked.
void registerTempForCleanup(const std::string& path);
void unregisterTempForCleanup(const std::string& path);
// Installs SIGINT, SIGTERM and SIGHUP handlers that unlink registered temporaries, then die of
// the same signal (so the exit status still says how the process ended).
void removeTempsOnSignals();

}  // namespace voxlink::format
