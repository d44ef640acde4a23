// SPDX-License-Identifier: BSD-3-Clause
// Dense Cholesky factorization of a symmetric positive definite matrix with a 1-norm condition
// estimate (Hager/Higham), the solver behind every per-location kriging system (Kriger::predict,
// cross-validation). Small systems only (neighbourhoods of a few hundred points; global kriging
// of a few thousand).
// Kept by hand rather than LAPACK (dpotrf + dpocon + dpotrs, as global_kriging.cpp uses): for 8-32
// unknowns LAPACK's call overhead made it 1.46-1.73x slower, at 64 as fast, and it rounds
// differently (1-24 % of solution values bit-identical), so outputs would change.
// voxlink_cholesky_bench 20000 (bench/cholesky_vs_lapack.cpp), 2 shared cores, load 11.7:
// ns per system, ours / LAPACK: n=8 2991/5174, 16 6960/11284, 32 23195/33925, 64 117094/116916.
#pragma once

#include <cstddef>
#include <vector>

namespace voxlink::geostat {

class Cholesky {
 public:
  // Factors a + jitter * I (row-major n x n, only the lower triangle is read).
  // Returns false when the matrix is not numerically positive definite.
  bool factor(const std::vector<double>& a, size_t n, double jitter);
  // Solves (A + jitter I) x = b in place.
  void solve(double* b) const;
  // The two halves of solve(): b <- L^-1 b, and b <- L^-T b.
  void solveLower(double* b) const;
  void solveUpper(double* b) const;
  // Estimate of the 1-norm condition number ||A|| ||A^-1|| of the factored matrix (a lower
  // bound that is almost always within a factor of 3 of the truth).
  double conditionEstimate() const;
  size_t size() const { return n_; }

 private:
  size_t n_ = 0;
  double norm1_ = 0;       // ||A + jitter I||_1
  std::vector<double> l_;  // lower factor, row-major
  mutable std::vector<double> work_, work2_;
};

}  // namespace voxlink::geostat
