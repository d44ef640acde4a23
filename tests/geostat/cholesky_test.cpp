// SPDX-License-Identifier: BSD-3-Clause
#include "geostat/cholesky.h"

#include <gtest/gtest.h>

#include <cmath>

namespace voxlink::geostat {
namespace {

TEST(Cholesky, SolvesAndEstimatesTheConditionOfADiagonalMatrix) {
  const std::vector<double> a = {4, 0, 0, 0, 1, 0, 0, 0, 1e-6};
  Cholesky c;
  ASSERT_TRUE(c.factor(a, 3, 0));
  double b[3] = {8, 3, 2e-6};
  c.solve(b);
  EXPECT_NEAR(b[0], 2, 1e-14);
  EXPECT_NEAR(b[1], 3, 1e-14);
  EXPECT_NEAR(b[2], 2, 1e-9);
  EXPECT_NEAR(c.conditionEstimate(), 4e6, 1e-3);  // exact for diagonal matrices
}

TEST(Cholesky, ConditionEstimateIsWithinAFactorOfThreeOfTheTruthForHilbert) {
  // Hilbert 5x5; the truth is ||H||_1 ||H^-1||_1 from the inverse column by column.
  std::vector<double> h(25);
  for (int i = 0; i < 5; ++i)
    for (int j = 0; j < 5; ++j) h[i * 5 + j] = 1.0 / (i + j + 1);
  Cholesky c;
  ASSERT_TRUE(c.factor(h, 5, 0));
  double normA = 0, normInv = 0;
  for (int j = 0; j < 5; ++j) {
    double e[5] = {0, 0, 0, 0, 0}, colA = 0, colInv = 0;
    e[j] = 1;
    c.solve(e);
    for (int i = 0; i < 5; ++i) {
      colInv += std::fabs(e[i]);
      colA += h[i * 5 + j];
    }
    normA = std::max(normA, colA);
    normInv = std::max(normInv, colInv);
  }
  const double truth = normA * normInv;
  EXPECT_NEAR(truth, 943656, 1);  // the known integer inverse gives exactly this
  const double estimate = c.conditionEstimate();
  EXPECT_LE(estimate, truth * 1.0001);
  EXPECT_GE(estimate, truth / 3.0);
}

TEST(Cholesky, RefusesIndefiniteAndSingularMatrices) {
  Cholesky c;
  EXPECT_FALSE(c.factor({1, 2, 2, 1}, 2, 0));
  EXPECT_FALSE(c.factor({1, 1, 1, 1}, 2, 0));
  EXPECT_TRUE(c.factor({1, 1, 1, 1}, 2, 1e-8));  // a jitter makes it definite
  EXPECT_GT(c.conditionEstimate(), 1e8);
}

}  // namespace
}  // namespace voxlink::geostat
