// SPDX-License-Identifier: BSD-3-Clause
// Opening inputs without blocking: a FIFO, socket or device named as an input would block open()
// or read() forever, so inputs must be regular files (checked with O_NONBLOCK + fstat, which
// does not wait for a writer).
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "base/error.h"

namespace voxlink {
inline namespace base {

// kIo unless `path` names a regular file (after symlinks); never blocks. `what` says what the
// file was meant to be ("transfer function") and goes into the message.
Status requireRegularFile(const std::string& path, std::string_view what = "input");

// The whole file, refusing non-regular files and files over maxBytes (kTooLarge).
Result<std::string> readRegularFile(const std::string& path, uint64_t maxBytes,
                                    std::string_view what = "input");

// At most the first maxBytes of a regular file (headers of large files).
Result<std::string> readRegularFilePrefix(const std::string& path, uint64_t maxBytes,
                                          std::string_view what = "input");

}  // namespace base
}  // namespace voxlink
