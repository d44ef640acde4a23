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

// finishColumn of spd_kernels.cpp on every lane: column j of L from the updated column j.
// `good` keeps, per lane, whether every pivot so far was positive and finite. The pivots' square
// roots and divisions are one vector operation each (they were four scalar ones).
[[gnu::always_inline]] inline void finishColumn(double* a, size_t j, size_t n, LaneBits& good) {
  double* cj = a + at(0, j, n, 0);
  const Lanes d = VOXLINK_LANES(cj + j * W);
  good &= (d > 0.0) & (d < INFINITY);
  Lanes root;
  for (size_t l = 0; l < W; ++l) root[l] = std::sqrt(d[l]);
  const Lanes inverse = 1.0 / root;
  VOXLINK_LANES(cj + j * W) = inverse;
  for (size_t i = j + 1; i < n; ++i) VOXLINK_LANES(cj + i * W) *= inverse;
}

// finishColumn's pivot alone: checks the diagonal element d and stores 1 / sqrt(d) there (a
// pointer, not a returned vector, which would change the baseline clone's ABI).
[[gnu::always_inline]] inline void pivot(double* diagonal, LaneBits& good) {
  const Lanes d = VOXLINK_LANES(diagonal);
  good &= (d > 0.0) & (d < INFINITY);
  Lanes root;
  for (size_t l = 0; l < W; ++l) root[l] = std::sqrt(d[l]);
  VOXLINK_LANES(diagonal) = 1.0 / root;
}

// Rows [i, i + kRows) of columns p and p + 1 receive the updates of every pair of columns
// (j, j + 1) before p, held in registers: the right-looking kernel loaded and stored each
// element once per pair; here each pair costs two loads per row and four multipliers.
template <size_t kRows>
[[gnu::always_inline]] inline void updatePairRows(double* a, size_t n, size_t p, size_t i) {
  double* c0 = a + at(0, p, n, 0);
  double* c1 = c0 + n * W;
  Lanes x0[kRows], x1[kRows];
#pragma GCC unroll 8
  for (size_t r = 0; r < kRows; ++r)
    x0[r] = VOXLINK_LANES(c0 + (i + r) * W), x1[r] = VOXLINK_LANES(c1 + (i + r) * W);
  for (size_t j = 0; j < p; j += 2) {
    const double* d0 = a + at(0, j, n, 0);
    const double* d1 = d0 + n * W;
    const Lanes m00 = VOXLINK_CONST_LANES(d0 + p * W), m01 = VOXLINK_CONST_LANES(d1 + p * W);
    const Lanes m10 = VOXLINK_CONST_LANES(d0 + (p + 1) * W),
                m11 = VOXLINK_CONST_LANES(d1 + (p + 1) * W);
#pragma GCC unroll 8
    for (size_t r = 0; r < kRows; ++r) {
      const Lanes u = VOXLINK_CONST_LANES(d0 + (i + r) * W),
                  v = VOXLINK_CONST_LANES(d1 + (i + r) * W);
      // The right-looking kernel's expression, contracted alike in every clone.
      x0[r] -= u * m00 + v * m01;
      x1[r] -= u * m10 + v * m11;
    }
  }
  // Row p of column p + 1 lies above the diagonal: never written.
#pragma GCC unroll 8
  for (size_t r = 0; r < kRows; ++r) {
    VOXLINK_LANES(c0 + (i + r) * W) = x0[r];
    if (i + r > p) VOXLINK_LANES(c1 + (i + r) * W) = x1[r];
  }
}

// The scalar kernel's two-columns-at-a-time right-looking order, computed left-looking: each
// element receives the same updates in the same order (pair by pair, then its own pair's),
// so the same bits. kN > 0 fixes the size. Inlined into each clone (a separate function would
// be built for the baseline only, without FMA).
template <size_t kN>
[[gnu::always_inline]] inline void factorLowerBody(double* a, size_t n, uint8_t* ok) {
  if constexpr (kN > 0) n = kN;
  LaneBits good = Lanes{} == Lanes{};  // all lanes true
  size_t p = 0;
  for (; p + 1 < n; p += 2) {
    // The pair's two pivot rows first: their square roots and divisions, the kernel's longest
    // chain, then overlap the updates of the rows below (finishColumn's operations, split).
    double* c0 = a + at(0, p, n, 0);
    double* c1 = a + at(0, p + 1, n, 0);
    updatePairRows<2>(a, n, p, p);
    pivot(c0 + p * W, good);
    const Lanes inverse0 = VOXLINK_CONST_LANES(c0 + p * W);
    VOXLINK_LANES(c0 + (p + 1) * W) *= inverse0;
    const Lanes l10 = VOXLINK_CONST_LANES(c0 + (p + 1) * W);
    VOXLINK_LANES(c1 + (p + 1) * W) -= VOXLINK_CONST_LANES(c0 + (p + 1) * W) * l10;
    pivot(c1 + (p + 1) * W, good);
    const Lanes inverse1 = VOXLINK_CONST_LANES(c1 + (p + 1) * W);
    size_t i = p + 2;
    for (; i + 4 <= n; i += 4) updatePairRows<4>(a, n, p, i);
    for (; i + 2 <= n; i += 2) updatePairRows<2>(a, n, p, i);
    if (i < n) updatePairRows<1>(a, n, p, i);
    for (size_t k = p + 2; k < n; ++k) {
      VOXLINK_LANES(c0 + k * W) *= inverse0;
      VOXLINK_LANES(c1 + k * W) -= VOXLINK_CONST_LANES(c0 + k * W) * l10;
      VOXLINK_LANES(c1 + k * W) *= inverse1;
    }
  }
  if (p < n) {  // the last column of an odd size: every pair's update, then its pivot
    double* c0 = a + at(0, p, n, 0);
    for (size_t j = 0; j < p; j += 2) {
      const double* d0 = a + at(0, j, n, 0);
      const double* d1 = d0 + n * W;
      const Lanes m0 = VOXLINK_CONST_LANES(d0 + p * W), m1 = VOXLINK_CONST_LANES(d1 + p * W);
      VOXLINK_LANES(c0 + p * W) -= m0 * m0 + m1 * m1;
    }
    finishColumn(a, p, n, good);
  }
  for (size_t l = 0; l < W; ++l) ok[l] = good[l] != 0;
}

}  // namespace

VOXLINK_BATCH_CLONES void factorLower(double* a, size_t n, uint8_t ok[kLanes]) {
  if (n == 32) return factorLowerBody<32>(a, n, ok);
  factorLowerBody<0>(a, n, ok);
}

VOXLINK_BATCH_CLONES void unpackLower(const double* a, size_t n, size_t count,
                                      double* const* factors, size_t ld) {
  static_assert(W == 4, "the transpose below is written for four lanes");
  for (size_t j = 0; j < n; ++j) {
    size_t i = j & ~size_t{3};
    for (; i + 4 <= n; i += 4) {  // rows i..i+3 of all lanes: a 4 x 4 transpose
      const double* in = a + at(i, j, n, 0);
      const Lanes r0 = VOXLINK_CONST_LANES(in), r1 = VOXLINK_CONST_LANES(in + W);
      const Lanes r2 = VOXLINK_CONST_LANES(in + 2 * W), r3 = VOXLINK_CONST_LANES(in + 3 * W);
      const Lanes t0 = __builtin_shufflevector(r0, r1, 0, 4, 2, 6);
      const Lanes t1 = __builtin_shufflevector(r0, r1, 1, 5, 3, 7);
      const Lanes t2 = __builtin_shufflevector(r2, r3, 0, 4, 2, 6);
      const Lanes t3 = __builtin_shufflevector(r2, r3, 1, 5, 3, 7);
      double* out = factors[0] + j * ld + i;
      VOXLINK_LANES(out) = __builtin_shufflevector(t0, t2, 0, 1, 4, 5);
      if (count > 1)
        VOXLINK_LANES(factors[1] + j * ld + i) = __builtin_shufflevector(t1, t3, 0, 1, 4, 5);
      if (count > 2)
        VOXLINK_LANES(factors[2] + j * ld + i) = __builtin_shufflevector(t0, t2, 2, 3, 6, 7);
      if (count > 3)
        VOXLINK_LANES(factors[3] + j * ld + i) = __builtin_shufflevector(t1, t3, 2, 3, 6, 7);
    }
    for (i = std::max(i, j); i < n; ++i)
      for (size_t lane = 0; lane < count; ++lane) factors[lane][j * ld + i] = a[at(i, j, n, lane)];
  }
}

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
