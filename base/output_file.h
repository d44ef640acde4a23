// SPDX-License-Identifier: BSD-3-Clause
// Safe creation of output files: every command writes to a temporary file beside the target
// and renames it into place. The temporary has a short unique name made with O_EXCL (so a
// symlink planted at a predictable name is never written through, and a 255-byte target name
// still fits), is removed if the process is stopped by SIGINT, SIGTERM or SIGHUP, and the target
// is checked first: it must not be the input, nor an existing non-regular file (/dev/null, a
// directory, a FIFO) that a rename would replace.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "base/error.h"

namespace voxlink {
inline namespace base {

// kInvalidArgument when `target` is empty, exists and is not a regular file, or is the same file
// (device and inode) as one of `inputs`.
Status checkOutputTarget(const std::string& target, const std::vector<std::string>& inputs = {});
// checkOutputTarget, and `target` must be none of `files`, the files `input` reads beside
// itself (a header's data files, a DICOM folder's slices, a scene's meshes): kInvalidArgument
// naming the file and the input.
Status checkOutputTarget(const std::string& target, const std::string& input,
                         const std::vector<std::string>& files);

// An open, empty temporary file in the target's directory: "<dir>/.vl-XXXXXX<suffix>", mode
// 0644, registered for removal on signals. The caller owns fd and path.
struct TempFile {
  int fd = -1;
  std::string path;      // for an unnamed file, /proc/self/fd/N (opens the same file)
  bool unnamed = false;  // O_TMPFILE: no name in the directory until committed
};
Result<TempFile> createTempBeside(const std::string& target, std::string_view suffix = "");

// Like createTempBeside, but where the file system supports O_TMPFILE (and /proc is mounted)
// the file has no name until commitTempFile links it: even kill -9 leaves nothing behind.
// Elsewhere it is a named temporary as above.
Result<TempFile> createUnnamedTempBeside(const std::string& target);

// Closes a finished temporary of either kind (the close is checked) and puts it in place of
// `target`: an unnamed one is linked under a fresh .vl-XXXXXX name, then renamed (linkat cannot
// replace an existing file). On failure nothing is left of it.
Status commitTempFile(const TempFile& temp, const std::string& target);

// Renames a finished temporary over `target` and forgets it for signal cleanup; on failure the
// temporary is removed.
Status commitTemp(const std::string& tempPath, const std::string& target);

// Writes `bytes` as the whole of `target` through an unnamed temporary: all or nothing.
Status writeWholeFile(const std::string& target, std::span<const uint8_t> bytes);
// The same for a file made of `pieces` written one after the other.
Status writeWholeFile(const std::string& target, std::span<const std::span<const uint8_t>> pieces);

// Removes a temporary (after a failure) and forgets it.
void discardTemp(const std::string& tempPath);

// Temporaries registered here are unlinked by the handlers installed below (async-signal-safe:
// fixed slots, no allocation in the handler). At most 32 at a time; more are not tracked.
void registerTempForCleanup(const std::string& path);
void unregisterTempForCleanup(const std::string& path);
// Installs SIGINT, SIGTERM, SIGHUP and SIGABRT handlers that unlink registered temporaries, then
// die of the same signal (so the exit status still says how the process ended).
void removeTempsOnSignals();
// Unlinks every registered temporary now (a program that caught an exception it cannot go on
// from, before it reports it).
void removeRegisteredTemps();

}  // namespace base
}  // namespace voxlink
