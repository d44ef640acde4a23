// SPDX-License-Identifier: BSD-3-Clause
#include "geostat/detail/spd_batch_kernels.h"

#include <algorithm>
#include <cmath>

// Built like spd_kernels.cpp (baseline and AVX2 + FMA, picked at load time), plus AVX-512: the
// lanes hold the scalar kernel's operations, and every clone with FMA contracts them alike.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define VOXLINK_BATCH_CLONES \
  __attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")))
#else
#define VOXLINK_BATCH_CLONES
#endif

namespace voxlink::geostat::spd::batch {
namespace {

constexpr size_t W = kLanes;

// finishColumn of spd_kernels.cpp on every lane: column j of L from the updated column j.
// The pivots' check is a loop of its own so that the square roots and divisions vectorize.
[[gnu::always_inline]] inline void finishColumn(double* a, size_t j, size_t n, uint8_t* ok) {
  double* cj = a + at(0, j, n, 0);
  for (size_t l = 0; l < W; ++l) ok[l] &= cj[j * W + l] > 0.0 && cj[j * W + l] < INFINITY;
  double inverse[W];
  for (size_t l = 0; l < W; ++l) {
    inverse[l] = 1.0 / std::sqrt(cj[j * W + l]);
    cj[j * W + l] = inverse[l];
  }
  for (size_t i = j + 1; i < n; ++i)
    for (size_t l = 0; l < W; ++l) cj[i * W + l] *= inverse[l];
}

// The scalar kernel's two-columns-at-a-time right-looking order; kN > 0 fixes the size. Inlined
// into each clone (a separate function would be built for the baseline only, without FMA).
template <size_t kN>
[[gnu::always_inline]] inline void factorLowerBody(double* a, size_t n, uint8_t* ok) {
  if constexpr (kN > 0) n = kN;
  size_t j = 0;
  for (; j + 1 < n; j += 2) {
    double* c0 = a + at(0, j, n, 0);
    double* c1 = a + at(0, j + 1, n, 0);
    finishColumn(a, j, n, ok);
    double l10[W];
    for (size_t l = 0; l < W; ++l) l10[l] = c0[(j + 1) * W + l];
    for (size_t i = j + 1; i < n; ++i)
      for (size_t l = 0; l < W; ++l) c1[i * W + l] -= c0[i * W + l] * l10[l];
    finishColumn(a, j + 1, n, ok);
    for (size_t k = j + 2; k < n; ++k) {
      double lk0[W], lk1[W];
      for (size_t l = 0; l < W; ++l) lk0[l] = c0[k * W + l], lk1[l] = c1[k * W + l];
      double* ck = a + at(0, k, n, 0);
      for (size_t i = k; i < n; ++i)
        for (size_t l = 0; l < W; ++l)
          ck[i * W + l] -= c0[i * W + l] * lk0[l] + c1[i * W + l] * lk1[l];
    }
  }
  if (j < n) finishColumn(a, j, n, ok);
}

}  // namespace

VOXLINK_BATCH_CLONES void factorLower(double* a, size_t n, uint8_t ok[kLanes]) {
  std::fill(ok, ok + W, uint8_t{1});
  if (n == 32) return factorLowerBody<32>(a, n, ok);
  factorLowerBody<0>(a, n, ok);
}

// All lanes of one element as one vector (GCC's vector extension: lane-wise operations, so each
// lane does exactly the scalar arithmetic); unaligned loads and stores.
using Lanes = double __attribute__((vector_size(W * sizeof(double)), aligned(sizeof(double))));
using LaneBits =
    long long __attribute__((vector_size(W * sizeof(double)), aligned(sizeof(double))));

// Macros, not functions: a function passing a 32-byte vector would change the baseline clone's
// ABI (-Wpsabi).
#define VOXLINK_LANES(p) (*reinterpret_cast<Lanes*>(p))
#define VOXLINK_CONST_LANES(p) (*reinterpret_cast<const Lanes*>(p))
#define VOXLINK_ABS(v) reinterpret_cast<Lanes>(reinterpret_cast<LaneBits>(v) & 0x7fffffffffffffffLL)

VOXLINK_BATCH_CLONES void norm1(const double* a, size_t n, double* work, double norm[kLanes]) {
  std::fill(work, work + n * W, 0.0);  // work[i * W + lane]: column i's sum
  // Four columns at a time: four independent chains of adds (one was latency-bound), while
  // each row still receives its terms in column order (the same bits).
  size_t j = 0;
  for (; j + 4 <= n; j += 4) {
    Lanes sum[4];
    for (size_t c = 0; c < 4; ++c) {
      const double* cc = a + at(0, j + c, n, 0);
      sum[c] = VOXLINK_ABS(VOXLINK_CONST_LANES(cc + (j + c) * W));
      for (size_t i = j + c + 1; i < j + 4; ++i) {
        const Lanes v = VOXLINK_ABS(VOXLINK_CONST_LANES(cc + i * W));
        sum[c] += v;
        VOXLINK_LANES(work + i * W) += v;
      }
    }
    const double* c0 = a + at(0, j, n, 0);
    const double* c1 = c0 + n * W;
    const double* c2 = c1 + n * W;
    const double* c3 = c2 + n * W;
    for (size_t i = j + 4; i < n; ++i) {
      const Lanes v0 = VOXLINK_ABS(VOXLINK_CONST_LANES(c0 + i * W)),
                  v1 = VOXLINK_ABS(VOXLINK_CONST_LANES(c1 + i * W));
      const Lanes v2 = VOXLINK_ABS(VOXLINK_CONST_LANES(c2 + i * W)),
                  v3 = VOXLINK_ABS(VOXLINK_CONST_LANES(c3 + i * W));
      sum[0] += v0, sum[1] += v1, sum[2] += v2, sum[3] += v3;
      VOXLINK_LANES(work + i * W) = (((VOXLINK_LANES(work + i * W) + v0) + v1) + v2) + v3;
    }
    for (size_t c = 0; c < 4; ++c) VOXLINK_LANES(work + (j + c) * W) += sum[c];
  }
  for (; j < n; ++j) {
    const double* cj = a + at(0, j, n, 0);
    Lanes sum = VOXLINK_ABS(VOXLINK_CONST_LANES(cj + j * W));
    for (size_t i = j + 1; i < n; ++i) {
      const Lanes v = VOXLINK_ABS(VOXLINK_CONST_LANES(cj + i * W));
      sum += v;
      VOXLINK_LANES(work + i * W) += v;
    }
    VOXLINK_LANES(work + j * W) += sum;
  }
  for (size_t l = 0; l < W; ++l) norm[l] = 0.0;
  for (size_t i = 0; i < n; ++i)
    for (size_t l = 0; l < W; ++l) norm[l] = std::max(norm[l], work[i * W + l]);
}

VOXLINK_BATCH_CLONES void inverseNormComparisonBound(const double* a, size_t n, double* work,
                                                     double bound[kLanes]) {
  double* x = work;  // x[i * W + lane]: M(L)^-1 1 (M(L): |l_ii| on the diagonal, -|l_ij| below)
  double* y = work + n * W;  // M(L)^-T 1
  std::fill(x, x + n * W, 1.0);
  for (size_t j = 0; j < n; ++j) {
    const double* cj = a + at(0, j, n, 0);
    const Lanes xj = VOXLINK_LANES(x + j * W) *= VOXLINK_CONST_LANES(cj + j * W);
    for (size_t i = j + 1; i < n; ++i)
      VOXLINK_LANES(x + i * W) += VOXLINK_ABS(VOXLINK_CONST_LANES(cj + i * W)) * xj;
  }
  for (size_t i = n; i-- > 0;) {  // the scalar kernel's four split sums per lane
    const double* ci = a + at(0, i, n, 0);
    Lanes s0 = {}, s1 = {}, s2 = {}, s3 = {};
    size_t k = i + 1;
    for (; k + 4 <= n; k += 4) {
      s0 += VOXLINK_ABS(VOXLINK_CONST_LANES(ci + k * W)) * VOXLINK_LANES(y + k * W);
      s1 += VOXLINK_ABS(VOXLINK_CONST_LANES(ci + (k + 1) * W)) * VOXLINK_LANES(y + (k + 1) * W);
      s2 += VOXLINK_ABS(VOXLINK_CONST_LANES(ci + (k + 2) * W)) * VOXLINK_LANES(y + (k + 2) * W);
      s3 += VOXLINK_ABS(VOXLINK_CONST_LANES(ci + (k + 3) * W)) * VOXLINK_LANES(y + (k + 3) * W);
    }
    for (; k < n; ++k)
      s0 += VOXLINK_ABS(VOXLINK_CONST_LANES(ci + k * W)) * VOXLINK_LANES(y + k * W);
    VOXLINK_LANES(y + i * W) = (1.0 + ((s0 + s1) + (s2 + s3))) * VOXLINK_CONST_LANES(ci + i * W);
  }
  double xMax[W], yMax[W];
  for (size_t l = 0; l < W; ++l) xMax[l] = yMax[l] = n == 0 ? 1.0 : 0.0;
  for (size_t i = 0; i < n; ++i)
    for (size_t l = 0; l < W; ++l) {
      xMax[l] = std::max(xMax[l], x[i * W + l]);
      yMax[l] = std::max(yMax[l], y[i * W + l]);
    }
  for (size_t l = 0; l < W; ++l) bound[l] = xMax[l] * yMax[l];
}

}  // namespace voxlink::geostat::spd::batch
