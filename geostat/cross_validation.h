// SPDX-License-Identifier: BSD-3-Clause
// Leave-one-out cross-validation: each sample kriged from the others with the same variogram
// and neighbourhood. A well-fitted model gives mean error ~ 0 and a mean standardized squared
// error (error^2 / kriging variance) ~ 1.
#pragma once

#include <vector>

#include "geostat/detail/kriging.h"

namespace voxlink::geostat {

struct CrossValidation {
  std::vector<double> predicted, variance;  // per sample after merging (NaN where none in reach)
  size_t evaluated = 0;
  double meanError = 0;  // mean(predicted - observed)
  double rmse = 0;
  double meanStandardizedSquaredError = 0;  // mean((predicted - observed)^2 / variance)
  double correlation = 0;                   // between predicted and observed
};

// Needs the samples the kriger was built from (after merging they are the kriger's own;
// pass them in the same order). Samples without any neighbour in reach are not evaluated.
Result<CrossValidation> leaveOneOut(const Kriger& kriger);

}  // namespace voxlink::geostat
