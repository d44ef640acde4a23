// SPDX-License-Identifier: BSD-3-Clause
#include "geostat/detail/spd_kernels.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <vector>

#include "tests/geostat/spd_test_util.h"

namespace voxlink::geostat {
namespace {

std::vector<double> covariances(size_t n, double r, unsigned seed) {
  std::mt19937 rng(seed);
  return test::randomCovariances(n, r, rng);
}

double norm1(const std::vector<double>& a, size_t n) {
  const size_t ld = spd::paddedSize(n);
  double worst = 0;
  for (size_t j = 0; j < n; ++j) {
    double sum = 0;
    for (size_t i = 0; i < n; ++i) sum += std::fabs(a[j * ld + i]);
    worst = std::max(worst, sum);
  }
  return worst;
}

TEST(SpdKernels, InverseNormBoundsAreAboveTheTrueNormAndTheL1BoundAtMostN15TimesIt) {
  for (size_t n : {1, 2, 5, 16, 31, 32, 33, 48}) {
    for (double range : {0.1, 1.0, 4.0}) {  // condition from ~1 to ~1e5
      std::vector<double> l = covariances(n, range, static_cast<unsigned>(n));
      const size_t ld = spd::paddedSize(n);
      ASSERT_TRUE(spd::factorLower(l.data(), n, ld)) << n;
      // The truth: ||A^-1||_1 from A^-1 column by column.
      double truth = 0;
      std::vector<double> column(n);
      for (size_t j = 0; j < n; ++j) {
        std::fill(column.begin(), column.end(), 0.0);
        column[j] = 1;
        spd::applyInverse(l.data(), n, ld, column.data());
        double sum = 0;
        for (double v : column) sum += std::fabs(v);
        truth = std::max(truth, sum);
      }
      // n (n + 1) doubles for the bound, 3 n for the estimate (more than n (n + 1) at n = 1).
      std::vector<double> work(std::max(n * (n + 1), 3 * n));
      const double bound = spd::inverseNormBound(l.data(), n, ld, work.data());
      EXPECT_GE(bound, truth * (1 - 1e-12)) << "n " << n << " range " << range;
      EXPECT_LE(bound, truth * std::pow(double(n), 1.5) * (1 + 1e-12)) << n << " " << range;
      const double comparison = spd::inverseNormComparisonBound(l.data(), n, ld, work.data());
      EXPECT_GE(comparison, truth * (1 - 1e-12)) << "n " << n << " range " << range;
      const double estimate = spd::inverseNormEstimate(l.data(), n, ld, work.data());
      EXPECT_LE(estimate, bound * (1 + 1e-12)) << n << " " << range;
    }
  }
}

TEST(SpdKernels, ApplyInverseIsTheTwoTriangularSolvesBitForBit) {
  for (size_t n : {3, 32, 45}) {
    std::vector<double> l = covariances(n, 1.0, 9);
    const size_t ld = spd::paddedSize(n);
    const double norm = norm1(l, n);
    ASSERT_TRUE(spd::factorLower(l.data(), n, ld));
    std::vector<double> b(n), c(n);
    for (size_t i = 0; i < n; ++i) b[i] = c[i] = std::sin(1.0 + double(i)) * norm;
    spd::applyInverse(l.data(), n, ld, b.data());
    spd::solveLower(l.data(), n, ld, c.data());
    spd::solveLowerTransposed(l.data(), n, ld, c.data());
    for (size_t i = 0; i < n; ++i) EXPECT_EQ(b[i], c[i]) << n << " " << i;
  }
}

}  // namespace
}  // namespace voxlink::geostat
