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

// n = 32 (ld 32) takes a register-held path (local kriging's size); it must give the general
// loop's bits (ld 36 takes that loop) and never read the upper triangle (NaN here).
TEST(SpdKernels, SolveLowerOfThirtyTwoIsTheGeneralLoopBitForBit) {
  constexpr size_t n = 32, wide = 36;
  std::vector<double> l = covariances(n, 1.0, 5);
  const double norm = norm1(l, n);
  ASSERT_TRUE(spd::factorLower(l.data(), n, n));
  std::vector<double> padded(wide * n, NAN);
  for (size_t j = 0; j < n; ++j)
    for (size_t i = 0; i < n; ++i) {
      if (i < j) l[j * n + i] = NAN;
      padded[j * wide + i] = l[j * n + i];
    }
  std::vector<double> b(n), c(n), d(n), e(n);
  for (size_t i = 0; i < n; ++i) {
    b[i] = c[i] = std::sin(1.0 + double(i)) * norm;
    d[i] = e[i] = std::cos(2.0 + double(i)) * norm;
  }
  spd::solveLower(l.data(), n, n, b.data());
  spd::solveLower(padded.data(), n, wide, c.data());
  for (size_t i = 0; i < n; ++i) ASSERT_EQ(b[i], c[i]) << i;
  std::vector<double> b2(n), d2(d);
  for (size_t i = 0; i < n; ++i) b2[i] = std::sin(1.0 + double(i)) * norm;
  spd::solveLower(l.data(), n, n, b2.data(), d2.data());
  spd::solveLower(padded.data(), n, wide, e.data());
  for (size_t i = 0; i < n; ++i) {
    EXPECT_EQ(b2[i], b[i]) << i;
    EXPECT_EQ(d2[i], e[i]) << i;
  }
}

// solveNodes32, one node or two interleaved (different factors), gives solveLower's and dot()'s
// bits, and reads no upper triangle (NaN here).
TEST(SpdKernels, SolveNodesOfThirtyTwoAreSolveLowerAndDotBitForBit) {
  constexpr size_t n = 32;
  std::vector<double> l[2] = {covariances(n, 1.0, 11), covariances(n, 0.3, 12)};
  std::vector<double> b[2], r[2], u[2];
  for (int k = 0; k < 2; ++k) {
    const double norm = norm1(l[k], n);
    ASSERT_TRUE(spd::factorLower(l[k].data(), n, n));
    for (size_t j = 0; j < n; ++j)
      for (size_t i = 0; i < j; ++i) l[k][j * n + i] = NAN;
    for (size_t i = 0; i < n; ++i) {
      b[k].push_back(std::sin(1.0 + double(i) + k) * norm);
      r[k].push_back(std::cos(3.0 + double(i) * (k + 1)));
      u[k].push_back(std::sin(0.5 * double(i) - k));
    }
  }
  for (size_t count : {1, 2}) {
    std::vector<double> solved[2] = {b[0], b[1]};
    spd::NodeSolve32 nodes[2];
    for (size_t k = 0; k < 2; ++k)
      nodes[k] = {
          l[k].data(), solved[k].data(), r[k].data(), k == 0 ? u[k].data() : nullptr, 0, 0, 0};
    spd::solveNodes32(nodes, count);
    for (size_t k = 0; k < count; ++k) {
      std::vector<double> y = b[k];
      spd::solveLower(l[k].data(), n, n, y.data());
      for (size_t i = 0; i < n; ++i) ASSERT_EQ(solved[k][i], y[i]) << count << " " << k << " " << i;
      EXPECT_EQ(nodes[k].yy, spd::dot(y.data(), y.data(), n));
      EXPECT_EQ(nodes[k].ry, spd::dot(r[k].data(), y.data(), n));
      if (k == 0) {
        EXPECT_EQ(nodes[k].uy, spd::dot(u[k].data(), y.data(), n));
      }
    }
  }
}

}  // namespace
}  // namespace voxlink::geostat
