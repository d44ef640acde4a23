// SPDX-License-Identifier: BSD-3-Clause
// The experimental (sample) variogram and a weighted least-squares fit of a model to it.
#pragma once

#include <vector>

#include "geostat/detail/variogram.h"
#include "geostat/point_set.h"

namespace voxlink::geostat {

struct VariogramBin {
  double lag = 0;    // mean pair distance in the bin
  double gamma = 0;  // mean of (z_i - z_j)^2 / 2
  uint64_t pairs = 0;
};

struct ExperimentalVariogramOptions {
  double cutoff = -1;        // < 0: a third of the bounding-box diagonal (gstat's default)
  double width = -1;         // < 0: cutoff / 15 (gstat's default)
  size_t maxSamples = 5000;  // larger sets use an evenly strided subset (O(n^2) pairs)
};

// Bins with at least one pair, in order of lag.
Result<std::vector<VariogramBin>> experimentalVariogram(
    const PointSet& points, const ExperimentalVariogramOptions& options = {});

struct VariogramFitOptions {
  VariogramType type = VariogramType::kSpherical;
  double smoothness = 0.5;  // Matern nu, kept fixed
  bool fitNugget = true;    // false: nugget fixed at 0
};

// Fits nugget, psill and range by weighted least squares with gstat's default weights
// (pairs / lag^2, fit.method = 7). For a fixed range the model is linear in nugget and psill,
// which are solved exactly (non-negative); the range is found by a log-spaced scan refined
// by golden-section search. Refuses when the variogram is flat zero (all values equal).
Result<VariogramParams> fitVariogram(const std::vector<VariogramBin>& bins,
                                     const VariogramFitOptions& options);

}  // namespace voxlink::geostat
