// SPDX-License-Identifier: BSD-3-Clause
// What pass 2 of the converter produces besides the bricks' bytes: where a slab's bricks go in
// the final sections, and what encoding measured (the decoded value range, the value and
// gradient errors, whether the source changed since pass 1). Threads and ranks each keep their
// own stats and fold them together with add().
#pragma once

#include <algorithm>
#include <cstdint>
#include <limits>

namespace voxlink::convert {

// Where pass 2 writes the bricks of one slab: occupied bricks [k0, k0 + ...) and voxels
// [v0, v0 + ...) of the final sections.
struct SlabOutput {
  uint64_t k0 = 0, v0 = 0;
  uint16_t* rows = nullptr;
  uint32_t* masks = nullptr;
  uint8_t* values = nullptr;
  uint16_t* gradients = nullptr;
};

// Pass 2 statistics of one worker; sums are integers so totals do not depend on job order.
struct EncodeStats {
  double valueMin = std::numeric_limits<double>::infinity();  // decoded, source units
  double valueMax = -std::numeric_limits<double>::infinity();
  double maxAbsError = 0, maxRelError = 0;
  uint64_t gradientSamples = 0;
  uint64_t gradientErrorNanoDeg = 0;
  double gradientMaxErrorDeg = 0;
  uint64_t zeroGradients = 0;
  bool countMismatch = false;  // the source changed between the passes

  // Folds in the stats of other bricks (another thread's or another rank's).
  void add(const EncodeStats& s) {
    valueMin = std::min(valueMin, s.valueMin);
    valueMax = std::max(valueMax, s.valueMax);
    maxAbsError = std::max(maxAbsError, s.maxAbsError);
    maxRelError = std::max(maxRelError, s.maxRelError);
    gradientSamples += s.gradientSamples;
    gradientErrorNanoDeg += s.gradientErrorNanoDeg;
    gradientMaxErrorDeg = std::max(gradientMaxErrorDeg, s.gradientMaxErrorDeg);
    zeroGradients += s.zeroGradients;
    countMismatch |= s.countMismatch;
  }
};

}  // namespace voxlink::convert
