// SPDX-License-Identifier: BSD-3-Clause
// The libFuzzer executable fuzz_<name>: compiled once per target with VOXLINK_FUZZ_TARGET set
// to the target's name (fuzz/CMakeLists.txt).
#include <cstdio>
#include <cstdlib>

#include "fuzz/fuzz_targets.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const voxlink::fuzz::FuzzTarget* target = [] {
    const auto* t = voxlink::fuzz::findFuzzTarget(VOXLINK_FUZZ_TARGET);
    if (!t) {
      std::fprintf(stderr, "no fuzz target named %s\n", VOXLINK_FUZZ_TARGET);
      std::abort();
    }
    return t;
  }();
  // Errors are the expected outcome for most inputs; only crashes and sanitizer reports count.
  // VOXLINK_FUZZ_VERBOSE=1 prints each input's outcome (to check seeds: fuzz_<name> FILE...).
  static const bool verbose = std::getenv("VOXLINK_FUZZ_VERBOSE") != nullptr;
  const voxlink::Status status = target->run({data, size});
  if (verbose) std::fprintf(stderr, "outcome: %s\n", status ? "ok" : status.message().c_str());
  return 0;
}
