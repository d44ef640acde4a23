// SPDX-License-Identifier: BSD-3-Clause
// exp() of many arguments with std::exp's bits: local kriging's pair covariances (exponential
// model) call it a few hundred times per fresh system, and one call per argument through libm
// was ~12 % of a 3-D node's time (docs/kriging.md, "Pair covariances as vectors").
#pragma once

#include <cstddef>

namespace voxlink::geostat {

// out[i] = std::exp(x[i]) bit for bit. Four at a time (AVX2 + FMA) with the operations of
// glibc's FMA exp (2.28 and later; a table of 2^(k/128), a degree-5 polynomial) when this
// process's std::exp is that one: checked once, at first use, against std::exp on arguments
// across its range. Otherwise, and for arguments outside [2^-54, 512) in magnitude, std::exp.
void expBatch(const double* x, double* out, size_t n);

// Whether expBatch runs four at a time here (the check above passed).
bool expBatchIsVectorized();

}  // namespace voxlink::geostat
