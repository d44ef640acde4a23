// SPDX-License-Identifier: BSD-3-Clause
// Some libraries end the process on damaged input (GDCM asserts, OpenVDB corrupts its heap)
// instead of reporting an error. A reader can first run the same library calls in a forked
// child: if the child dies, the input is refused with a clear error and never read in-process.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>

namespace voxlink::sources {

struct ProbeOutcome {
  // Killed by a signal, or ended with a failure status before finishing (a sanitizer's report
  // exits with status 1 instead of a signal).
  bool died = false;
  int signal = 0;                     // 0 when it exited
  int exitStatus = 0;                 // when it exited
  std::optional<uint32_t> lastMark;   // the last mark(i) the child made
  std::optional<std::string> thrown;  // what() of an exception that ended `work`
};

// Runs `work` in a child process with stderr sent to /dev/null. `work` may call mark(i) to say
// which item it is on. An exception from `work` comes back as `thrown`, so the caller need not
// repeat a slow failing read. When no child can be started the outcome is empty (not died, not
// thrown): the caller then reads unguarded; so does a child that runs past 5 minutes (killed).
using MarkFn = std::function<void(uint32_t)>;
// "Segmentation fault", "exit status 1": how a child that died ended, for messages.
std::string describeDeath(const ProbeOutcome& outcome);

// `memoryBytes` > 0 bounds the child's address space to what it had at the fork plus that many
// bytes (RLIMIT_AS; relative, because a sanitizer's shadow memory is already terabytes of
// reserved addresses): a library that would allocate more gets std::bad_alloc, which comes back
// as `thrown`, or dies, instead of taking the machine's memory.
ProbeOutcome probeInChild(const std::function<void(const MarkFn& mark)>& work,
                          uint64_t memoryBytes = 0);

}  // namespace voxlink::sources
