// SPDX-License-Identifier: BSD-3-Clause
#include "geostat/blas_threads.h"

// Not in cblas.h: OpenBLAS's own shutdown of its thread server (driver/others/blas_server.c),
// which its fork handler uses too; exec_blas starts the server again when it is next needed.
extern "C" int blas_thread_shutdown_(void);

namespace voxlink::geostat {

void stopIdleBlasThreads() { blas_thread_shutdown_(); }

}  // namespace voxlink::geostat
