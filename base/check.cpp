// SPDX-License-Identifier: BSD-3-Clause
#include "base/check.h"

#include <cstdio>
#include <cstdlib>

namespace voxlink {
inline namespace base {

void checkFailed(const char* file, int line, const char* macro, const char* expression,
                 const std::string& detail) {
  std::fprintf(stderr, "%s:%d: %s(%s) failed%s%s\n", file, line, macro, expression,
               detail.empty() ? "" : ": ", detail.c_str());
  std::fflush(stderr);
  std::abort();
}

}  // namespace base
}  // namespace voxlink
