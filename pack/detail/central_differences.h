// SPDX-License-Identifier: BSD-3-Clause
// The two vectorizable loops of the gradient predictor of packed files (internal to
// pack/detail/brick_gradient_predictor.h): central differences at a brick's cells, and values to
// reals through a lookup table.
#pragma once

#include <cstdint>
#include <cstring>

namespace voxlink::pack::detail {

// g_a[j] = (value[c + s_a] - value[c - s_a]) * half_a at each cell c = cell[j]. The arrays do not
// overlap, which lets the compiler gather with vector loads; the float version also has clones
// for wider vectors (lane by lane the same operations, so the same bits).
template <class Real>
[[gnu::always_inline]] inline void centralDifferences(const Real* __restrict value,
                                                      const uint32_t* __restrict cell,
                                                      uint32_t count, const uint32_t* stride,
                                                      const Real* half, Real* __restrict g0,
                                                      Real* __restrict g1, Real* __restrict g2) {
  const uint32_t s0 = stride[0], s1 = stride[1], s2 = stride[2];
  const Real h0 = half[0], h1 = half[1], h2 = half[2];
  for (uint32_t j = 0; j < count; ++j) {
    const uint32_t c = cell[j];
    g0[j] = (value[c + s0] - value[c - s0]) * h0;
    g1[j] = (value[c + s1] - value[c - s1]) * h1;
    g2[j] = (value[c + s2] - value[c - s2]) * h2;
  }
}

// Defined in gradient_predictor.cpp, with clones for wider vectors.
void centralDifferencesFloat(const float* __restrict value, const uint32_t* __restrict cell,
                             uint32_t count, const uint32_t* stride, const float* half,
                             float* __restrict g0, float* __restrict g1, float* __restrict g2);

// out[j] = table[the j-th value of type Stored at `bytes`] for j < count (in a loop of its own:
// inlined into the predictor, it reloaded its bound from the stack at every value).
template <class Stored, class Real>
[[gnu::noinline]] void lookUp(const uint8_t* __restrict bytes, const Real* __restrict table,
                              uint32_t count, Real* __restrict out) {
  for (uint32_t j = 0; j < count; ++j) {
    Stored x;
    std::memcpy(&x, bytes + sizeof(Stored) * j, sizeof(Stored));
    out[j] = table[x];
  }
}

}  // namespace voxlink::pack::detail
