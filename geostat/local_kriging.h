// Local kriging (the k nearest samples per node) of a whole grid, brick by brick:
//  - one k-d tree query per brick of nodes finds every sample that can be among the k nearest
//    of any of its nodes (those within d_k+1(centre) + 2 x the brick's half-diagonal), and each
//    node picks its k from those few candidates, with the tree's order (distance, then index),
//    so the neighbour sets are exactly the ones Kriger::predict would use;
//  - the covariances among the candidates are evaluated once per brick;
//  - nodes whose neighbour sets agree share one factorization, kept in a per-thread cache;
//  - each node then costs one triangular solve: with L L^T = C, y = L^-1 c, u = L^-1 1 and
//    r = L^-1 (z - m) (u and r per factorization), the ordinary kriging estimate is
//    m + r.y - mu u.r and its variance sill - y.y + mu (u.y - 1), mu = (u.y - 1) / u.u.
// No approximation: the results equal Kriger::predict's to rounding (tested).
#pragma once

#include "geostat/krige_grid.h"

namespace voxlink::kriging {

Result<KrigingSummary> krigeGridLocal(const Kriger& kriger, const GridSpec& grid,
                                      const SliceSink& sink, const GridKrigingOptions& options);

}  // namespace voxlink::kriging
