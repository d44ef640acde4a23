// SPDX-License-Identifier: BSD-3-Clause
// Line-by-line reading of a text file, plain or the single member of a .zip archive (libzip),
// with rewind; what the GSLIB/GEO-EAS reader streams from.
#pragma once

#include <memory>
#include <string>
#include <string_view>

#include "base/error.h"

namespace voxlink::sources {

class TextStream {
 public:
  virtual ~TextStream() = default;
  // Next line without its end-of-line characters ("\n" or "\r\n"); false at the end.
  virtual Result<bool> nextLine(std::string_view& line) = 0;
  virtual Status rewind() = 0;
  // Lines returned since the last rewind (1-based number of the last line).
  uint64_t lineNumber() const { return line_; }
  const std::string& name() const { return name_; }

 protected:
  uint64_t line_ = 0;
  std::string name_;  // "file" or "archive.zip:member" for messages
};

// Opens `path`; a name ending in .zip opens its only file member.
Result<std::unique_ptr<TextStream>> openTextStream(const std::string& path);

}  // namespace voxlink::sources
