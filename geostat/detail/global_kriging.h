// SPDX-License-Identifier: BSD-3-Clause
// Global kriging (every sample in every system) of a whole grid with level-3 BLAS: the
// covariance matrix is built and factored once (LAPACK dpotrf, condition from dpocon, the same
// jitter ladder as Kriger::predict), then blocks of nodes are solved together: Y = L^-1 K for
// the block's node covariances K (one dtrsm), and each node's estimate and variance follow
// from its column of Y with three dot products (see local_kriging.h for the formulas).
// OpenBLAS runs single-threaded inside the grid's worker threads, multi-threaded for the
// factorization. No approximation: the results equal Kriger::predict's to rounding (tested).
#pragma once

#include "geostat/krige_grid.h"

namespace voxlink::geostat {

// Bytes global kriging of `samples` samples needs (the factor, and one block per thread).
uint64_t globalKrigingBytes(size_t samples, unsigned threads);

Result<KrigingSummary> krigeGridGlobal(const Kriger& kriger, const GridSpec& grid,
                                       const GridPart& part, const NodeRunSink& sink,
                                       const GridKrigingOptions& options);

}  // namespace voxlink::geostat
