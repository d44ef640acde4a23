// SPDX-License-Identifier: BSD-3-Clause
// OpenBLAS's worker threads and short jobs. Debian's OpenBLAS (the pthread build) starts its
// workers when the library loads, and each spins about 2^28 cycles (~0.1 s) waiting for work
// before it sleeps. On two cores that is a core taken from the first tenth of a second of every
// process: Walker Lake's 32-neighbour grid solved in 0.09-0.12 s beside the spinning worker
// and in 0.05-0.06 s with OPENBLAS_NUM_THREADS=1 (docs/kriging.md).
#pragma once

namespace voxlink::geostat {

// Stops OpenBLAS's idle workers now. OpenBLAS starts them again at its next threaded call (the
// global solver's large factorizations), so nothing else changes. Call it once, early, from
// the executable.
void stopIdleBlasThreads();

}  // namespace voxlink::geostat
