// SPDX-License-Identifier: BSD-3-Clause
// Some libraries (libnifti, libpng under OpenImageIO) print warnings and errors straight to
// stderr, which would add lines to our one-line messages. While a StderrCapture lives, file
// descriptor 2 points at a temporary file; firstLine() returns what was printed, so a failed
// call can quote the library's reason in our own message. Captures may nest or overlap across
// threads: the first one redirects, the last one restores.
#pragma once

#include <string>

namespace voxlink {
inline namespace base {

class StderrCapture {
 public:
  StderrCapture();
  ~StderrCapture();
  StderrCapture(const StderrCapture&) = delete;
  StderrCapture& operator=(const StderrCapture&) = delete;

  // The first non-empty line printed so far (by any thread while the capture was active),
  // without the trailing newline; empty if nothing was printed.
  std::string firstLine() const;
};

}  // namespace base
}  // namespace voxlink
