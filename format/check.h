// Invariants that must hold in release builds too. A failed VOXLINK_CHECK is a bug in VoxLink,
// never bad input (bad input gets a Status): the process stops with the file, line and
// condition instead of running on into undefined behaviour.
#pragma once

#include <cstdio>
#include <cstdlib>

namespace voxlink {

[[noreturn, gnu::cold]] inline void checkFailed(const char* file, int line, const char* condition,
                                                const char* what) {
  std::fprintf(stderr, "%s:%d: VOXLINK_CHECK(%s) failed: %s\n", file, line, condition, what);
  std::fflush(stderr);
  std::abort();
}

}  // namespace voxlink

// VOXLINK_CHECK(condition, "what went wrong"): aborts when `condition` is false, in every build.
#define VOXLINK_CHECK(condition, what)                              \
  do {                                                              \
    if (!(condition)) [[unlikely]]                                  \
      ::voxlink::checkFailed(__FILE__, __LINE__, #condition, what); \
  } while (0)
