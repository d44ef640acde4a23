// SPDX-License-Identifier: BSD-3-Clause
// Covariance matrices for the SPD kernel tests.
#pragma once

#include <array>
#include <cmath>
#include <random>
#include <vector>

#include "geostat/detail/spd_kernels.h"

namespace voxlink::geostat::test {

// Exponential covariances of n random points in a unit cube (range r), column-major, padded
// to spd::paddedSize(n) rows.
inline std::vector<double> randomCovariances(size_t n, double r, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<std::array<double, 3>> p(n);
  for (auto& q : p) q = {u(rng), u(rng), u(rng)};
  const size_t ld = spd::paddedSize(n);
  std::vector<double> a(ld * n, 0.0);
  for (size_t j = 0; j < n; ++j)
    for (size_t i = 0; i < n; ++i) {
      const double h = std::hypot(p[i][0] - p[j][0], p[i][1] - p[j][1], p[i][2] - p[j][2]);
      a[j * ld + i] = std::exp(-3 * h / r);
    }
  return a;
}

}  // namespace voxlink::geostat::test
