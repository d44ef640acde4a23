// SPDX-License-Identifier: BSD-3-Clause
// Cholesky kernels for the small symmetric positive definite systems of local kriging (tens of
// unknowns), column-major so every inner loop is an axpy or a split-accumulator dot product that
// the compiler vectorizes; on x86-64 they are also built for x86-64-v3 (AVX2 + FMA) and picked
// at run time. cholesky.cpp's row-major dot products are latency bound at these sizes.
#pragma once

#include <cstddef>

namespace voxlink::geostat::spd {

// Leading dimension for an n x n column-major matrix: n rounded up to whole 32-byte rows.
constexpr size_t paddedSize(size_t n) { return (n + 3) & ~size_t{3}; }

// Factors the lower triangle of a (column-major, leading dimension ld) in place into L with
// A = L L^T, storing 1 / l_jj on the diagonal (the solves multiply instead of divide, which
// shortens their dependency chain). Returns false when a pivot is not positive and finite.
bool factorLower(double* a, size_t n, size_t ld);
// b <- L^-1 b; the second form solves for two right-hand sides in one pass.
void solveLower(const double* l, size_t n, size_t ld, double* b);
void solveLower(const double* l, size_t n, size_t ld, double* b, double* c);
// b <- L^-T b.
void solveLowerTransposed(const double* l, size_t n, size_t ld, double* b);
double dot(const double* a, const double* b, size_t n);

// A kriging node's solve for n = ld = 32 (local kriging's usual size): b <- L^-1 b, then
// yy = b.b, ry = r.b and, where u is not null, uy = u.b, each with the bits of solveLower and
// dot. Two nodes at once: each solve alone is one chain of dependent operations, so two
// interleaved take little longer than one.
struct NodeSolve32 {
  const double* l;
  double* b;
  const double* r;
  const double* u;
  double yy, ry, uy;
};
void solveNodes32(NodeSolve32* nodes, size_t count);  // count: 1 or 2
// b <- A^-1 b = L^-T L^-1 b (the two solves above in one call).
void applyInverse(const double* l, size_t n, size_t ld, double* b);
// Hager/Higham estimate of ||A^-1||_1 from the factor (a lower bound almost always within a
// factor of 3); `work` holds 3 n doubles. Times ||A||_1 it is the 1-norm condition estimate.
double inverseNormEstimate(const double* l, size_t n, size_t ld, double* work);
// An upper bound of ||A^-1||_1 from L^-1 (n^3 / 3 flops that vectorize, fewer than the
// estimate's triangular solves cost); `work` holds n (n + 1) doubles.
double inverseNormBound(const double* l, size_t n, size_t ld, double* work);
// A looser upper bound of ||A^-1||_1 (typically 10^3-10^4 x above it) from two triangular
// solves with |L| (2 n^2 flops); `work` holds 2 n doubles.
double inverseNormComparisonBound(const double* l, size_t n, size_t ld, double* work);

}  // namespace voxlink::geostat::spd
