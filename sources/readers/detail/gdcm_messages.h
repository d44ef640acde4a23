// SPDX-License-Identifier: BSD-3-Clause
// GDCM reports problems by printing several lines to stderr. While one of these lives, its
// warnings and errors go to a buffer instead, so a failed read can name GDCM's reason in our
// own one-line error. GDCM's streams are global: DICOM files are read on one thread.
#pragma once

#include <ostream>
#include <sstream>
#include <string>

namespace voxlink::sources {

class GdcmMessages {
 public:
  GdcmMessages();
  ~GdcmMessages();
  GdcmMessages(const GdcmMessages&) = delete;
  GdcmMessages& operator=(const GdcmMessages&) = delete;

  // The first message line (not GDCM's "Warning: In file, line ..." location lines), as
  // "; GDCM: <line>", or empty when GDCM said nothing.
  std::string reason() const;

 private:
  std::ostringstream buffer_;
  std::ostream* warning_;
  std::ostream* error_;
};

}  // namespace voxlink::sources
