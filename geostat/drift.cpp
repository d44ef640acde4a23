// SPDX-License-Identifier: BSD-3-Clause
#include "geostat/detail/drift.h"

#include <cmath>

#include "geostat/detail/spd_kernels.h"

namespace voxlink::geostat {
namespace {

// A term whose remaining pivot falls below this fraction of its own squared norm lies in the
// span of the earlier ones (rounding leaves ~1e-16 there; real terms stay near 1).
constexpr double kDependentPivot = 1e-10;

}  // namespace

size_t DriftBasis::terms() const {
  if (!constant) return 0;
  const size_t d = static_cast<size_t>(dimension);
  size_t p = 1;
  if (kind != DriftKind::kNone) p += d;
  if (kind == DriftKind::kQuadratic) p += d * (d + 1) / 2;
  return p + (external ? 1 : 0);
}

void DriftBasis::at(const Point3& q, double externalValue, double* f) const {
  if (!constant) return;
  size_t j = 0;
  f[j++] = 1.0;
  if (kind != DriftKind::kNone) {  // ordinary kriging (every node of it) skips the divisions
    const int d = dimension;
    const double s[3] = {q[0] / coordinateScale, q[1] / coordinateScale, q[2] / coordinateScale};
    for (int a = 0; a < d; ++a) f[j++] = s[a];
    if (kind == DriftKind::kQuadratic)
      for (int a = 0; a < d; ++a)
        for (int b = a; b < d; ++b) f[j++] = s[a] * s[b];
  }
  if (external) f[j] = (externalValue - externalMean) / externalScale;
}

void DriftSystem::factor(const double* u, size_t n, size_t ld, size_t p) {
  p_ = p;
  dropped_ = 0;
  g_.assign(p * p, 0.0);
  kept_.assign(p, 1);
  for (size_t i = 0; i < p; ++i)
    for (size_t j = 0; j <= i; ++j) g_[i * p + j] = spd::dot(u + i * ld, u + j * ld, n);
  // Cholesky, row by row; a dependent term's row and column leave the factor.
  for (size_t i = 0; i < p; ++i) {
    const double norm = g_[i * p + i];
    for (size_t j = 0; j <= i; ++j) {
      if (!kept_[j]) continue;
      double s = g_[i * p + j];
      for (size_t k = 0; k < j; ++k)
        if (kept_[k]) s -= g_[i * p + k] * g_[j * p + k];
      if (j < i) {
        g_[i * p + j] = s / g_[j * p + j];
      } else if (s > kDependentPivot * norm && std::isfinite(s) && norm > 0) {
        g_[i * p + i] = std::sqrt(s);
      } else {
        kept_[i] = 0;
        ++dropped_;
      }
    }
  }
}

void DriftSystem::solve(double* a) const {
  const size_t p = p_;
  for (size_t i = 0; i < p; ++i) {
    if (!kept_[i]) {
      a[i] = 0;
      continue;
    }
    double s = a[i];
    for (size_t k = 0; k < i; ++k)
      if (kept_[k]) s -= g_[i * p + k] * a[k];
    a[i] = s / g_[i * p + i];
  }
  for (size_t i = p; i-- > 0;) {
    if (!kept_[i]) continue;
    double s = a[i];
    for (size_t k = i + 1; k < p; ++k)
      if (kept_[k]) s -= g_[k * p + i] * a[k];
    a[i] = s / g_[i * p + i];
  }
}

void DriftSystem::correct(const double* u, size_t n, const double* y, const double* f0,
                          const double* ur, double* scratch, double& value,
                          double& variance) const {
  for (size_t j = 0; j < p_; ++j) scratch[j] = spd::dot(u + j * n, y, n);
  correctWithProducts(scratch, f0, ur, scratch, value, variance);
}

void DriftSystem::correctAny(const double* uy, const double* f0, const double* ur, double* scratch,
                             double& value, double& variance) const {
  double* a = scratch;
  double* mu = scratch + p_;
  for (size_t j = 0; j < p_; ++j) mu[j] = a[j] = uy[j] - f0[j];
  solve(mu);
  for (size_t j = 0; j < p_; ++j) {
    value -= mu[j] * ur[j];
    variance += mu[j] * a[j];
  }
}

}  // namespace voxlink::geostat
