// SPDX-License-Identifier: BSD-3-Clause
#include "sources/readers/detail/gdcm_messages.h"

#include <gdcmTrace.h>

namespace voxlink::sources {

GdcmMessages::GdcmMessages()
    : warning_(&gdcm::Trace::GetWarningStream()), error_(&gdcm::Trace::GetErrorStream()) {
  gdcm::Trace::SetWarningStream(buffer_);
  gdcm::Trace::SetErrorStream(buffer_);
}

GdcmMessages::~GdcmMessages() {
  gdcm::Trace::SetWarningStream(*warning_);
  gdcm::Trace::SetErrorStream(*error_);
}

std::string GdcmMessages::reason() const {
  std::istringstream lines(buffer_.str());
  for (std::string line; std::getline(lines, line);) {
    if (line.empty() || line.rfind("Warning: In ", 0) == 0 || line.rfind("Error: In ", 0) == 0 ||
        line.rfind("Debug: In ", 0) == 0)
      continue;
    return "; GDCM: " + line;
  }
  return {};
}

}  // namespace voxlink::sources
