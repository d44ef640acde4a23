// SPDX-License-Identifier: BSD-3-Clause
#include "geostat/variogram_fit.h"

#include <gtest/gtest.h>

#include <cmath>

namespace voxlink::geostat {
namespace {

TEST(VariogramFit, RecoversTheModelFromItsOwnBins) {
  for (VariogramType t : {VariogramType::kExponential, VariogramType::kSpherical,
                          VariogramType::kGaussian, VariogramType::kMatern}) {
    const VariogramParams truth{t, 0.3, 2.0, 37.0, 1.5};
    const Variogram v = Variogram::make(truth).value();
    std::vector<VariogramBin> bins;
    for (int i = 1; i <= 20; ++i)
      bins.push_back({i * 4.0, v.gamma(i * 4.0), uint64_t(100 + 10 * i)});
    auto fit = fitVariogram(bins, {t, 1.5, true});
    ASSERT_TRUE(fit) << fit.message();
    EXPECT_NEAR(fit->nugget, 0.3, 1e-4) << variogramTypeName(t);
    EXPECT_NEAR(fit->psill, 2.0, 1e-4) << variogramTypeName(t);
    EXPECT_NEAR(fit->range, 37.0, 1e-3) << variogramTypeName(t);
  }
}

TEST(VariogramFit, ExperimentalVariogramOfAKnownConfiguration) {
  // Three samples on a line: pairs at distance 1 (twice) and 2.
  PointSet s;
  s.coords = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}};
  s.values = {0, 2, 6};
  auto bins = experimentalVariogram(s, {.cutoff = 3, .width = 1.5});
  ASSERT_TRUE(bins);
  ASSERT_EQ(bins->size(), 2u);
  EXPECT_EQ((*bins)[0].pairs, 2u);
  EXPECT_DOUBLE_EQ((*bins)[0].gamma, (0.5 * 4 + 0.5 * 16) / 2);
  EXPECT_EQ((*bins)[1].pairs, 1u);
  EXPECT_DOUBLE_EQ((*bins)[1].gamma, 0.5 * 36);
}

TEST(VariogramFit, RefusesFlatDataWithAMessage) {
  PointSet s;
  for (int i = 0; i < 30; ++i) {
    s.coords.push_back({double(i % 6), double(i / 6), 0});
    s.values.push_back(4.0);
  }
  auto bins = experimentalVariogram(s);
  ASSERT_TRUE(bins);
  auto fit = fitVariogram(*bins, {VariogramType::kSpherical});
  ASSERT_FALSE(fit);
  EXPECT_EQ(fit.code(), ErrorCode::kInvalidArgument);
  EXPECT_NE(fit.message().find("all values equal"), std::string::npos);
  PointSet one;
  one.coords = {{0, 0, 0}};
  one.values = {1};
  EXPECT_FALSE(experimentalVariogram(one));
}

}  // namespace
}  // namespace voxlink::geostat
