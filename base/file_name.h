// SPDX-License-Identifier: BSD-3-Clause
// File-name suffix tests that ignore case: FOOT.NRRD is a NRRD file, as every reader here and
// every peer tool (ParaView, teem, OpenVDB's vdb_print) treats it.
#pragma once

#include <cctype>
#include <string_view>

namespace voxlink {
inline namespace base {

inline bool hasExtension(std::string_view path, std::string_view extension) {
  if (path.size() < extension.size()) return false;
  const std::string_view tail = path.substr(path.size() - extension.size());
  for (size_t i = 0; i < tail.size(); ++i)
    if (std::tolower(static_cast<unsigned char>(tail[i])) !=
        std::tolower(static_cast<unsigned char>(extension[i])))
      return false;
  return true;
}

}  // namespace base
}  // namespace voxlink
