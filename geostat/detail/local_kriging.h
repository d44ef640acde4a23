// SPDX-License-Identifier: BSD-3-Clause
// Local kriging (the k nearest samples per node) of a whole grid, brick by brick:
//  - one k-d tree query per brick of nodes finds every sample that can be among the k nearest
//    of any of its nodes (those within d_k+1(centre) + 2 x the brick's half-diagonal), and each
//    node picks its k from those few candidates, with the tree's order (distance, then index),
//    so the neighbour sets are exactly the ones Kriger::predict would use;
//  - the covariances among the candidates are evaluated once per brick;
//  - nodes whose neighbour sets agree share one factorization, kept in a per-thread cache;
//  - each node then costs one triangular solve: with L L^T = C, y = L^-1 c, U = L^-1 F (F: the
//    drift terms at the samples, the column of ones for ordinary kriging) and r = L^-1 (z - m)
//    (U, r and the small G = U^T U per factorization), the estimate is m + r.y - mu.(U^T r) and
//    the variance sill - y.y + mu.a, a = U^T y - f0, mu = G^-1 a (drift.h). Ordinary kriging:
//    mu = (u.y - 1) / u.u.
// No approximation: the results equal Kriger::predict's to rounding (tested).
#pragma once

#include "geostat/krige_grid.h"

namespace voxlink::geostat {

Result<KrigingSummary> krigeGridLocal(const Kriger& kriger, const GridSpec& grid,
                                      const GridPart& part, const NodeRunSink& sink,
                                      const GridKrigingOptions& options);

}  // namespace voxlink::geostat
