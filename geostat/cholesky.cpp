// SPDX-License-Identifier: BSD-3-Clause
#include "geostat/cholesky.h"

#include <algorithm>
#include <cmath>

namespace voxlink::geostat {

bool Cholesky::factor(const std::vector<double>& a, size_t n, double jitter) {
  n_ = n;
  l_.assign(n * n, 0.0);
  norm1_ = 0;
  for (size_t j = 0; j < n; ++j) {
    double col = 0;
    for (size_t i = 0; i < n; ++i) {
      const double v = i >= j ? a[i * n + j] : a[j * n + i];
      col += std::fabs(v) + (i == j ? jitter : 0.0);
    }
    norm1_ = std::max(norm1_, col);
  }
  for (size_t j = 0; j < n; ++j) {
    double d = a[j * n + j] + jitter;
    const double* lj = &l_[j * n];
    for (size_t k = 0; k < j; ++k) d -= lj[k] * lj[k];
    if (!(d > 0.0) || !std::isfinite(d)) return false;
    const double djj = std::sqrt(d);
    l_[j * n + j] = djj;
    for (size_t i = j + 1; i < n; ++i) {
      const double* li = &l_[i * n];
      double s = a[i * n + j];
      for (size_t k = 0; k < j; ++k) s -= li[k] * lj[k];
      l_[i * n + j] = s / djj;
    }
  }
  return true;
}

void Cholesky::solveLower(double* b) const {
  const size_t n = n_;
  for (size_t i = 0; i < n; ++i) {  // L y = b
    const double* li = &l_[i * n];
    double s = b[i];
    for (size_t k = 0; k < i; ++k) s -= li[k] * b[k];
    b[i] = s / li[i];
  }
}

void Cholesky::solveUpper(double* b) const {
  const size_t n = n_;
  for (size_t i = n; i-- > 0;) {  // L^T x = y, by rows of L (contiguous) rather than columns
    const double* li = &l_[i * n];
    const double xi = b[i] / li[i];
    b[i] = xi;
    for (size_t k = 0; k < i; ++k) b[k] -= li[k] * xi;
  }
}

void Cholesky::solve(double* b) const {
  solveLower(b);
  solveUpper(b);
}

double Cholesky::conditionEstimate() const {
  const size_t n = n_;
  if (n == 0) return 1.0;
  // Hager's method: maximise ||A^-1 x||_1 over the unit 1-norm ball (A^-1 is symmetric).
  work_.assign(n, 1.0 / static_cast<double>(n));
  double estimate = 0;
  for (int iter = 0; iter < 5; ++iter) {
    std::vector<double> x = work_;
    solve(work_.data());
    double norm = 0;
    for (double v : work_) norm += std::fabs(v);
    if (iter > 0 && norm <= estimate) break;
    estimate = norm;
    work2_.resize(n);
    for (size_t i = 0; i < n; ++i) work2_[i] = work_[i] >= 0 ? 1.0 : -1.0;
    solve(work2_.data());
    size_t j = 0;
    double zx = 0;
    for (size_t i = 0; i < n; ++i) {
      zx += work2_[i] * x[i];
      if (std::fabs(work2_[i]) > std::fabs(work2_[j])) j = i;
    }
    if (std::fabs(work2_[j]) <= zx) break;
    work_.assign(n, 0.0);
    work_[j] = 1.0;
  }
  // Higham's alternating-sign probe catches matrices Hager's iteration underestimates.
  work_.resize(n);
  for (size_t i = 0; i < n; ++i)
    work_[i] = (i % 2 ? -1.0 : 1.0) * (1.0 + static_cast<double>(i) / std::max<size_t>(n - 1, 1));
  solve(work_.data());
  double alt = 0;
  for (double v : work_) alt += std::fabs(v);
  estimate = std::max(estimate, 2.0 * alt / (3.0 * static_cast<double>(n)));
  return norm1_ * estimate;
}

}  // namespace voxlink::geostat
