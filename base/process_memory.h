// SPDX-License-Identifier: BSD-3-Clause
// How much memory this process may allocate: the machine's physical memory (swap not counted),
// or less under a container's memory limit (cgroup) or `ulimit -v`. Long jobs whose size is known
// up front (scene builds, random fields) compare their needs with it and refuse at once, instead of
// failing after minutes with std::bad_alloc or being killed by the kernel's OOM killer (Linux
// overcommits: a single allocation larger than what is free still succeeds, and touching it kills
// the process).
#pragma once

#include <cstdint>

namespace voxlink {
inline namespace base {

uint64_t memoryForThisProcess();

}  // namespace base
}  // namespace voxlink
