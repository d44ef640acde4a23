// SPDX-License-Identifier: BSD-3-Clause
#include "geostat/detail/spd_kernels.h"

#include <algorithm>
#include <cmath>

// GCC builds each kernel twice (baseline and AVX2 + FMA) and an ifunc picks one at load time.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define VOXLINK_VECTOR_CLONES __attribute__((target_clones("arch=x86-64-v3", "default")))
#define VOXLINK_NODE_CLONES \
  __attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")))
#else
#define VOXLINK_VECTOR_CLONES
#define VOXLINK_NODE_CLONES
#endif

namespace voxlink::geostat::spd {

namespace {

// Turns column j (already updated by the columns before it) into column j of L.
inline bool finishColumn(double* cj, size_t j, size_t n) {
  const double d = cj[j];
  if (!(d > 0.0) || !std::isfinite(d)) return false;
  const double inverse = 1.0 / std::sqrt(d);
  cj[j] = inverse;
  for (size_t i = j + 1; i < n; ++i) cj[i] *= inverse;
  return true;
}

// Four split accumulators: the sum's latency chain is a quarter as long.
inline double dotInline(const double* a, const double* b, size_t n) {
  double s0 = 0, s1 = 0, s2 = 0, s3 = 0;
  size_t i = 0;
  for (; i + 4 <= n; i += 4) {
    s0 += a[i] * b[i];
    s1 += a[i + 1] * b[i + 1];
    s2 += a[i + 2] * b[i + 2];
    s3 += a[i + 3] * b[i + 3];
  }
  for (; i < n; ++i) s0 += a[i] * b[i];
  return (s0 + s1) + (s2 + s3);
}

}  // namespace

// Right-looking, two columns at a time: each trailing column is read and written once per pair
// (a rank-2 axpy), which halves the memory traffic of the update that dominates. kN > 0 fixes
// the size (the same arithmetic, unrolled by the compiler).
template <size_t kN>
inline bool factorLowerBody(double* a, size_t n, size_t ld) {
  if constexpr (kN > 0) n = kN, ld = paddedSize(kN);
  size_t j = 0;
  for (; j + 1 < n; j += 2) {
    double* c0 = a + j * ld;
    double* c1 = c0 + ld;
    if (!finishColumn(c0, j, n)) return false;
    const double l10 = c0[j + 1];
    for (size_t i = j + 1; i < n; ++i) c1[i] -= c0[i] * l10;
    if (!finishColumn(c1, j + 1, n)) return false;
    for (size_t k = j + 2; k < n; ++k) {
      const double lk0 = c0[k], lk1 = c1[k];
      double* ck = a + k * ld;
      for (size_t i = k; i < n; ++i) ck[i] -= c0[i] * lk0 + c1[i] * lk1;
    }
  }
  return j == n || finishColumn(a + j * ld, j, n);
}

VOXLINK_VECTOR_CLONES bool factorLower(double* a, size_t n, size_t ld) {
  if (n == 32 && ld == 32) return factorLowerBody<32>(a, n, ld);
  return factorLowerBody<0>(a, n, ld);
}

// solveLower for n = 32 (ld 32) with b held in eight 4-wide registers: the loop above stores b
// and reloads it shifted by one element each column, and those overlapping unaligned reloads
// miss store forwarding (most of the per-node solve's time). Each element sees the same
// operations in the same order: the columns before its block as vector updates, those of its
// own block as scalars.
__attribute__((always_inline)) inline void solveLower32(const double* l, double* b) {
  using Vec = double __attribute__((vector_size(32), aligned(8)));
  constexpr size_t kN = 32, kBlocks = kN / 4;
  Vec v[kBlocks];
  for (size_t s = 0; s < kBlocks; ++s) __builtin_memcpy(&v[s], b + 4 * s, sizeof(Vec));
#pragma GCC unroll 8
  for (size_t r = 0; r < kBlocks; ++r) {
    double x[4] = {v[r][0], v[r][1], v[r][2], v[r][3]};
#pragma GCC unroll 4
    for (size_t t = 0; t < 4; ++t) {
      const double* cj = l + (4 * r + t) * kN;
      x[t] *= cj[4 * r + t];
#pragma GCC unroll 4
      for (size_t i = t + 1; i < 4; ++i) x[i] -= cj[4 * r + i] * x[t];
    }
    v[r] = Vec{x[0], x[1], x[2], x[3]};
#pragma GCC unroll 4
    for (size_t t = 0; t < 4; ++t) {
      const double* cj = l + (4 * r + t) * kN;
#pragma GCC unroll 8
      for (size_t s = r + 1; s < kBlocks; ++s) {
        Vec c;
        __builtin_memcpy(&c, cj + 4 * s, sizeof(Vec));
        v[s] -= c * x[t];
      }
    }
  }
  for (size_t s = 0; s < kBlocks; ++s) __builtin_memcpy(b + 4 * s, &v[s], sizeof(Vec));
}

VOXLINK_VECTOR_CLONES void solveLower(const double* l, size_t n, size_t ld, double* b) {
  if (n == 32 && ld == 32) return solveLower32(l, b);
  for (size_t j = 0; j < n; ++j) {
    const double* cj = l + j * ld;
    const double bj = b[j] * cj[j];
    b[j] = bj;
    for (size_t i = j + 1; i < n; ++i) b[i] -= cj[i] * bj;
  }
}

VOXLINK_VECTOR_CLONES void solveLower(const double* l, size_t n, size_t ld, double* b, double* c) {
  if (n == 32 && ld == 32) {  // each right-hand side's elements see the same operations alone
    solveLower32(l, b);
    return solveLower32(l, c);
  }
  for (size_t j = 0; j < n; ++j) {
    const double* cj = l + j * ld;
    const double bj = b[j] * cj[j], cj_ = c[j] * cj[j];
    b[j] = bj;
    c[j] = cj_;
    for (size_t i = j + 1; i < n; ++i) {
      b[i] -= cj[i] * bj;
      c[i] -= cj[i] * cj_;
    }
  }
}

// solveLower32 and the dot products of kNodes nodes, statement by statement as there and in
// dotInline (four split sums, here the four lanes of one vector), so the same contraction and
// bits. Built for x86-64-v4 as well: two nodes' 16 vectors fit its 32 registers.
template <size_t kNodes>
[[gnu::always_inline]] inline void solveNodes32Body(NodeSolve32* nodes) {
  using Vec = double __attribute__((vector_size(32), aligned(8)));
  constexpr size_t kN = 32, kBlocks = kN / 4;
  Vec v[kNodes][kBlocks];
  const double* l[kNodes];
  for (size_t k = 0; k < kNodes; ++k) {
    l[k] = nodes[k].l;
    for (size_t s = 0; s < kBlocks; ++s) __builtin_memcpy(&v[k][s], nodes[k].b + 4 * s, 32);
  }
#pragma GCC unroll 8
  for (size_t r = 0; r < kBlocks; ++r) {
    double x[kNodes][4];
    for (size_t k = 0; k < kNodes; ++k)
      for (size_t t = 0; t < 4; ++t) x[k][t] = v[k][r][t];
#pragma GCC unroll 4
    for (size_t t = 0; t < 4; ++t)
      for (size_t k = 0; k < kNodes; ++k) {
        const double* cj = l[k] + (4 * r + t) * kN;
        x[k][t] *= cj[4 * r + t];
#pragma GCC unroll 4
        for (size_t i = t + 1; i < 4; ++i) x[k][i] -= cj[4 * r + i] * x[k][t];
      }
    for (size_t k = 0; k < kNodes; ++k) v[k][r] = Vec{x[k][0], x[k][1], x[k][2], x[k][3]};
#pragma GCC unroll 4
    for (size_t t = 0; t < 4; ++t)
      for (size_t k = 0; k < kNodes; ++k) {
        const double* cj = l[k] + (4 * r + t) * kN;
#pragma GCC unroll 8
        for (size_t s = r + 1; s < kBlocks; ++s) {
          Vec c;
          __builtin_memcpy(&c, cj + 4 * s, 32);
          v[k][s] -= c * x[k][t];
        }
      }
  }
  for (size_t k = 0; k < kNodes; ++k) {
    Vec yy = {}, ry = {}, uy = {};
    for (size_t s = 0; s < kBlocks; ++s) {
      __builtin_memcpy(nodes[k].b + 4 * s, &v[k][s], 32);
      Vec rs;
      __builtin_memcpy(&rs, nodes[k].r + 4 * s, 32);
      yy += v[k][s] * v[k][s];
      ry += rs * v[k][s];
      if (nodes[k].u) {
        Vec us;
        __builtin_memcpy(&us, nodes[k].u + 4 * s, 32);
        uy += us * v[k][s];
      }
    }
    nodes[k].yy = (yy[0] + yy[1]) + (yy[2] + yy[3]);
    nodes[k].ry = (ry[0] + ry[1]) + (ry[2] + ry[3]);
    nodes[k].uy = (uy[0] + uy[1]) + (uy[2] + uy[3]);
  }
}

VOXLINK_NODE_CLONES void solveNodes32(NodeSolve32* nodes, size_t count) {
  if (count == 2) return solveNodes32Body<2>(nodes);
  solveNodes32Body<1>(nodes);
}

VOXLINK_VECTOR_CLONES double dot(const double* a, const double* b, size_t n) {
  return dotInline(a, b, n);
}

void solveLowerTransposed(const double* l, size_t n, size_t ld, double* b) {
  for (size_t i = n; i-- > 0;) {
    const double* ci = l + i * ld;
    b[i] = (b[i] - dot(ci + i + 1, b + i + 1, n - i - 1)) * ci[i];
  }
}

// The two solves in one call, so the short dot products of the transposed solve are inlined
// rather than dispatched one by one (the same arithmetic as the two calls).
VOXLINK_VECTOR_CLONES void applyInverse(const double* l, size_t n, size_t ld, double* b) {
  for (size_t j = 0; j < n; ++j) {
    const double* cj = l + j * ld;
    const double bj = b[j] * cj[j];
    b[j] = bj;
    for (size_t i = j + 1; i < n; ++i) b[i] -= cj[i] * bj;
  }
  for (size_t i = n; i-- > 0;) {
    const double* ci = l + i * ld;
    b[i] = (b[i] - dotInline(ci + i + 1, b + i + 1, n - i - 1)) * ci[i];
  }
}

// X = L^-1 row by row (row-major, n x n; the right-looking updates of a row are independent
// axpys), then min(||X||_1 ||X||_inf, sqrt(n) ||X||_F^2): each is an upper bound of
// ||A^-1||_1 = ||X^T X||_1. kN > 0 fixes the size for the compiler.
template <size_t kN>
inline double inverseNormBoundBody(const double* l, size_t n, size_t ld, double* x) {
  if constexpr (kN > 0) n = kN, ld = paddedSize(kN);
  std::fill(x, x + n * n, 0.0);
  for (size_t j = 0; j < n; ++j) x[j * n + j] = 1.0;
  for (size_t j = 0; j < n; ++j) {
    const double* cj = l + j * ld;
    double* xj = x + j * n;
    for (size_t c = 0; c <= j; ++c) xj[c] *= cj[j];
    for (size_t i = j + 1; i < n; ++i) {
      double* xi = x + i * n;
      const double lij = cj[i];
      for (size_t c = 0; c <= j; ++c) xi[c] -= lij * xj[c];
    }
  }
  double frobenius = 0, rowMax = 0;
  double* column = x + n * n;  // n more doubles of work
  std::fill(column, column + n, 0.0);
  for (size_t i = 0; i < n; ++i) {
    const double* xi = x + i * n;
    double row = 0;
    for (size_t c = 0; c <= i; ++c) {
      const double a = std::fabs(xi[c]);
      row += a;
      column[c] += a;
      frobenius += a * a;
    }
    rowMax = std::max(rowMax, row);
  }
  const double columnMax = *std::max_element(column, column + n);
  return std::min(columnMax * rowMax, std::sqrt(double(n)) * frobenius);
}

VOXLINK_VECTOR_CLONES double inverseNormBound(const double* l, size_t n, size_t ld, double* work) {
  if (n == 0) return 1.0;
  if (n == 32 && ld == 32) return inverseNormBoundBody<32>(l, n, ld, work);
  return inverseNormBoundBody<0>(l, n, ld, work);
}

// |L^-1| <= M(L)^-1 entrywise, M(L) the comparison matrix (|l_ii| on the diagonal, -|l_ij|
// below; Higham, Accuracy and Stability, Thm 8.12), so ||L^-1||_inf <= max(M^-1 e) and
// ||L^-1||_1 <= max(M^-T e). Sums of positive terms: no cancellation, rounding stays relative.
VOXLINK_VECTOR_CLONES double inverseNormComparisonBound(const double* l, size_t n, size_t ld,
                                                        double* work) {
  if (n == 0) return 1.0;
  double* x = work;
  double* y = work + n;
  std::fill(x, x + n, 1.0);
  for (size_t j = 0; j < n; ++j) {
    const double* cj = l + j * ld;
    const double xj = x[j] * cj[j];
    x[j] = xj;
    for (size_t i = j + 1; i < n; ++i) x[i] += std::fabs(cj[i]) * xj;
  }
  // Split accumulators as in dotInline: one running sum was a chain of n^2 / 2 dependent adds
  // (every term is >= 0, so the order moves only the last bits of a bound).
  for (size_t i = n; i-- > 0;) {
    const double* ci = l + i * ld;
    double s0 = 0, s1 = 0, s2 = 0, s3 = 0;
    size_t k = i + 1;
    for (; k + 4 <= n; k += 4) {
      s0 += std::fabs(ci[k]) * y[k];
      s1 += std::fabs(ci[k + 1]) * y[k + 1];
      s2 += std::fabs(ci[k + 2]) * y[k + 2];
      s3 += std::fabs(ci[k + 3]) * y[k + 3];
    }
    for (; k < n; ++k) s0 += std::fabs(ci[k]) * y[k];
    y[i] = (1.0 + ((s0 + s1) + (s2 + s3))) * ci[i];
  }
  return *std::max_element(x, x + n) * *std::max_element(y, y + n);
}

double inverseNormEstimate(const double* l, size_t n, size_t ld, double* work) {
  if (n == 0) return 1.0;
  double* x = work;
  double* y = work + n;
  double* z = work + 2 * n;
  auto norm1 = [n](const double* v) {
    double s = 0;
    for (size_t i = 0; i < n; ++i) s += std::fabs(v[i]);
    return s;
  };
  // Hager's method: maximise ||A^-1 x||_1 over the unit 1-norm ball (A^-1 is symmetric).
  std::fill(y, y + n, 1.0 / static_cast<double>(n));
  double estimate = 0;
  for (int iter = 0; iter < 5; ++iter) {
    std::copy(y, y + n, x);
    applyInverse(l, n, ld, y);
    const double norm = norm1(y);
    if (iter > 0 && norm <= estimate) break;
    estimate = norm;
    for (size_t i = 0; i < n; ++i) z[i] = y[i] >= 0 ? 1.0 : -1.0;
    applyInverse(l, n, ld, z);
    size_t j = 0;
    double zx = 0;
    for (size_t i = 0; i < n; ++i) {
      zx += z[i] * x[i];
      if (std::fabs(z[i]) > std::fabs(z[j])) j = i;
    }
    if (std::fabs(z[j]) <= zx) break;
    std::fill(y, y + n, 0.0);
    y[j] = 1.0;
  }
  // Higham's alternating-sign probe catches matrices Hager's iteration underestimates.
  for (size_t i = 0; i < n; ++i)
    y[i] = (i % 2 ? -1.0 : 1.0) * (1.0 + static_cast<double>(i) / std::max<size_t>(n - 1, 1));
  applyInverse(l, n, ld, y);
  return std::max(estimate, 2.0 * norm1(y) / (3.0 * static_cast<double>(n)));
}

}  // namespace voxlink::geostat::spd
