// SPDX-License-Identifier: BSD-3-Clause
// fuzz_replay TARGET FILE...: runs inputs through a fuzz entry point without libFuzzer (any
// compiler) and prints each outcome, to check seeds or look at a kept crash input in a debugger.
#include <cstdio>
#include <fstream>
#include <iterator>
#include <vector>

#include "fuzz/fuzz_targets.h"

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: fuzz_replay TARGET FILE...\ntargets:");
    for (const auto& t : voxlink::fuzz::fuzzTargets())
      std::fprintf(stderr, " %.*s", static_cast<int>(t.name.size()), t.name.data());
    std::fprintf(stderr, "\n");
    return 2;
  }
  const auto* target = voxlink::fuzz::findFuzzTarget(argv[1]);
  if (!target) {
    std::fprintf(stderr, "fuzz_replay: no target named %s\n", argv[1]);
    return 2;
  }
  for (int i = 2; i < argc; ++i) {
    std::ifstream in(argv[i], std::ios::binary);
    if (!in) {
      std::fprintf(stderr, "fuzz_replay: cannot read %s\n", argv[i]);
      return 2;
    }
    const std::vector<uint8_t> bytes{std::istreambuf_iterator<char>(in), {}};
    const voxlink::Status status = target->run(bytes);
    std::printf("%s: %s\n", argv[i], status ? "ok" : status.message().c_str());
  }
  return 0;
}
