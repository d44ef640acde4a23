// SPDX-License-Identifier: BSD-3-Clause
#include "geostat/detail/variogram.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <vector>

namespace voxlink::geostat {
namespace {

Variogram make(VariogramType type, double nugget, double psill, double range, double nu = 0.5) {
  auto v = Variogram::make({type, nugget, psill, range, nu});
  EXPECT_TRUE(v) << v.message();
  return *v;
}

TEST(Variogram, PracticalRangeIsWhereCorrelationFallsToExpMinusThree) {
  for (VariogramType t :
       {VariogramType::kExponential, VariogramType::kGaussian, VariogramType::kMatern}) {
    for (double nu : {0.3, 0.5, 1.5, 3.0}) {
      const Variogram v = make(t, 0, 2, 30, nu);
      EXPECT_NEAR(v.correlation(30), std::exp(-3.0), 1e-9) << variogramTypeName(t) << " nu " << nu;
      EXPECT_GT(v.correlation(29), v.correlation(31));
    }
  }
  const Variogram sph = make(VariogramType::kSpherical, 0, 2, 30);
  EXPECT_EQ(sph.correlation(30), 0.0);
  EXPECT_GT(sph.correlation(29.9), 0.0);
}

TEST(Variogram, MaternWithHalfSmoothnessIsExponential) {
  const Variogram m = make(VariogramType::kMatern, 0.1, 1, 25, 0.5);
  const Variogram e = make(VariogramType::kExponential, 0.1, 1, 25);
  for (double h : {0.01, 1.0, 5.0, 12.5, 25.0, 60.0})
    EXPECT_NEAR(m.gamma(h), e.gamma(h), 1e-9) << h;
  EXPECT_NEAR(m.maternScale(), 25.0 / 3.0, 1e-6);  // gstat range of the exponential
}

TEST(Variogram, NuggetOnlyAppliesAwayFromZero) {
  const Variogram v = make(VariogramType::kSpherical, 0.25, 0.75, 10);
  EXPECT_EQ(v.gamma(0), 0.0);
  EXPECT_NEAR(v.gamma(1e-9), 0.25, 1e-9);
  EXPECT_EQ(v.covariance(0), 1.0);
  EXPECT_NEAR(v.covariance(1e-9), 0.75, 1e-9);
  EXPECT_NEAR(v.gamma(10), 1.0, 1e-15);
  EXPECT_NEAR(v.gamma(5), 0.25 + 0.75 * (1.5 * 0.5 - 0.5 * 0.125), 1e-15);
}

// Local kriging's right-hand sides and pair covariances come from the batched forms: they must
// give the same bits as covariance(sqrt(d2)) and covariance(h) one by one, at 0, inside, at and
// beyond the range (whichever clone, AVX2 or not, this machine runs).
TEST(Variogram, BatchedCovariancesEqualOneByOne) {
  std::vector<double> squared{0.0, 1e-300, 1e-18, 0.25, 1.0, 2.0, 17.3, 99.99, 100.0, 100.01, 1e6};
  for (int i = 1; i < 200; ++i) squared.push_back(0.731 * i);  // past the 4-wide vector tail
  for (VariogramType t : {VariogramType::kExponential, VariogramType::kSpherical,
                          VariogramType::kGaussian, VariogramType::kMatern}) {
    const Variogram v = make(t, 0.3, 1.7, 10, 1.5);
    std::vector<double> out(squared.size(), NAN);
    v.covariancesOfSquared(squared.data(), out.data(), squared.size());
    for (size_t i = 0; i < squared.size(); ++i) {
      const double expected = v.covariance(std::sqrt(squared[i]));
      EXPECT_EQ(std::memcmp(&out[i], &expected, sizeof(double)), 0)
          << variogramTypeName(t) << " d2 " << squared[i] << ": " << out[i] << " vs " << expected;
    }
    std::vector<double> distance(squared.size()), direct(squared.size(), NAN);
    for (size_t i = 0; i < squared.size(); ++i) distance[i] = std::sqrt(squared[i]);
    v.covariances(distance.data(), direct.data(), distance.size());
    for (size_t i = 0; i < distance.size(); ++i) {
      const double expected = v.covariance(distance[i]);
      EXPECT_EQ(std::memcmp(&direct[i], &expected, sizeof(double)), 0)
          << variogramTypeName(t) << " h " << distance[i] << ": " << direct[i] << " vs "
          << expected;
    }
  }
}

TEST(Variogram, ParsesModelsAndRejectsBadOnes) {
  auto p = parseVariogram("sph:nugget=0.1,sill=1,range=40");
  ASSERT_TRUE(p) << p.message();
  EXPECT_EQ(p->type, VariogramType::kSpherical);
  EXPECT_DOUBLE_EQ(p->psill, 0.9);
  auto m = parseVariogram("mat:psill=2,range=10,nu=1.5");
  ASSERT_TRUE(m);
  EXPECT_DOUBLE_EQ(m->smoothness, 1.5);
  struct Bad {
    const char* text;
    const char* mentions;
  };
  for (const Bad& bad :
       {Bad{"cubic:range=3", "cubic"}, Bad{"exp:psill=1", "range"}, Bad{"exp:range=-1", "range"},
        Bad{"exp:range=3,nugget=-1", "nugget"}, Bad{"exp:range=3,foo=2", "foo"},
        Bad{"exp:range=abc", "abc"}, Bad{"mat:range=3,nu=0", "smoothness"},
        Bad{"exp:range=3,psill=0,nugget=0", "sill"}}) {
    auto r = parseVariogram(bad.text);
    ASSERT_FALSE(r) << bad.text;
    EXPECT_EQ(r.code(), ErrorCode::kInvalidArgument);
    EXPECT_NE(r.message().find(bad.mentions), std::string::npos) << r.message();
  }
}

}  // namespace
}  // namespace voxlink::geostat
