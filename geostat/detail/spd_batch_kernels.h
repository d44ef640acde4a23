// SPDX-License-Identifier: BSD-3-Clause
// The Cholesky kernels of spd_kernels.h for kLanes independent systems at once, one system per
// SIMD lane ("compact" layout: element (i, j) of every lane side by side), so each operation is
// a full-width vector operation with no horizontal step and no short tails. Each lane performs
// the scalar kernel's operations in the scalar kernel's order, so its results are the same bits
// (spd_batch_kernels_test.cpp checks this: FMA contraction must come out alike, which is why
// the comparison bound, whose reductions GCC contracts differently per loop shape, equals the
// scalar one only to rounding); local kriging factors the nodes of a brick that need
// fresh systems kLanes at a time (local_kriging.cpp).
#pragma once

#include <cstddef>
#include <cstdint>

namespace voxlink::geostat::spd::batch {

// Four lanes: one AVX2 vector of doubles, and four 32 x 32 systems (16.5 KiB of lower
// triangles) stay in L1; eight (AVX-512) measured no faster on this machine (docs/kriging.md).
constexpr size_t kLanes = 4;

// Element (i, j) of lane `lane` of n x n systems stored in the compact layout.
constexpr size_t at(size_t i, size_t j, size_t n, size_t lane) {
  return (j * n + i) * kLanes + lane;
}

// spd::factorLower on every lane (lower triangle only; 1 / l_jj on the diagonal). ok[lane] is
// 0 where a pivot is not positive and finite (that lane's values are then meaningless).
void factorLower(double* a, size_t n, uint8_t ok[kLanes]);

// Lane l's lower triangle (element (i, j), i >= j) to factors[l][j * ld + i] for l < count,
// ld >= n. Four rows of four lanes are transposed in registers at a time, so the first block of
// a column may also write up to three rows above its diagonal (values never read).
void unpackLower(const double* a, size_t n, size_t count, double* const* factors, size_t ld);

// The 1-norm of every lane's symmetric matrix from its lower triangle: column sums of |a_ij|,
// added as local kriging's gather() adds them (the same bits; no multiplications). `work` holds
// n kLanes doubles.
void norm1(const double* a, size_t n, double* work, double norm[kLanes]);

// spd::inverseNormComparisonBound on every lane of factors from factorLower: the same sums in
// the same order per lane, but the scalar kernel's FMA contraction differs (its bound's last
// bits may differ; it is a bound either way, doubled for rounding where it is used). `work`
// holds 2 n kLanes doubles.
void inverseNormComparisonBound(const double* a, size_t n, double* work, double bound[kLanes]);

}  // namespace voxlink::geostat::spd::batch
