// SPDX-License-Identifier: BSD-3-Clause
// The defining properties of kriging: exact interpolation, zero variance at samples, unbiased
// weights, symmetry, and local == global when the neighbourhood holds every sample.
#include <gtest/gtest.h>

#include <numeric>

#include "tests/geostat/kriging_test_util.h"

namespace voxlink::geostat {
namespace {

using test::kriger;
using test::model;
using test::randomPoints;

class Exactness : public ::testing::TestWithParam<std::tuple<VariogramType, size_t>> {};

TEST_P(Exactness, InterpolatesSamplesWithZeroVarianceWhenThereIsNoNugget) {
  const auto [type, neighbours] = GetParam();
  const PointSet s = randomPoints(200, 11);
  const Kriger k = kriger(s, model(type, 0, 9, 40, 1.5), {.maxNeighbours = neighbours});
  KrigingWorkspace ws;
  for (size_t i = 0; i < s.size(); ++i) {
    auto p = k.predict(s.coords[i], ws);
    ASSERT_TRUE(p) << p.message();
    EXPECT_NEAR(p->value, s.values[i], 1e-6 * (1 + std::fabs(s.values[i]))) << i;
    EXPECT_LE(p->variance, 1e-6 * 9) << i;
  }
}

INSTANTIATE_TEST_SUITE_P(Models, Exactness,
                         ::testing::Combine(::testing::Values(VariogramType::kExponential,
                                                              VariogramType::kSpherical,
                                                              VariogramType::kMatern),
                                            ::testing::Values(size_t{0}, size_t{16})));

TEST(Kriging, WithANuggetSamplesStillGetTheirOwnValueAndZeroVariance) {
  // gstat's convention: a prediction location that coincides with a sample reproduces it.
  const PointSet s = randomPoints(50, 2);
  const Kriger k = kriger(s, model(VariogramType::kSpherical, 2, 7, 30));
  KrigingWorkspace ws;
  auto p = k.predict(s.coords[7], ws);
  ASSERT_TRUE(p);
  EXPECT_NEAR(p->value, s.values[7], 1e-8);
  EXPECT_NEAR(p->variance, 0, 1e-8);
}

TEST(Kriging, OrdinaryWeightsSumToOneSimpleWeightsNeedNot) {
  const PointSet s = randomPoints(120, 3);
  KrigingWorkspace ws;
  const Kriger ok =
      kriger(s, model(VariogramType::kExponential, 0.5, 8, 25), {.maxNeighbours = 24});
  const Kriger sk = kriger(s, model(VariogramType::kExponential, 0.5, 8, 25),
                           {.kind = KrigingKind::kSimple, .simpleMean = 10, .maxNeighbours = 24});
  for (const Point3& q : {Point3{50, 50, 0}, Point3{1, 99, 0}, Point3{170, 40, 0}}) {
    ASSERT_TRUE(ok.predict(q, ws));
    EXPECT_NEAR(std::accumulate(ws.weights.begin(), ws.weights.end(), 0.0), 1.0, 1e-12);
    ASSERT_TRUE(sk.predict(q, ws));
    const double skSum = std::accumulate(ws.weights.begin(), ws.weights.end(), 0.0);
    EXPECT_LT(skSum, 1.0);  // simple kriging leans on the known mean away from data
  }
  // Far outside the data: ordinary kriging falls back to a weighted mean, simple kriging to
  // the known mean with the full sill as variance.
  auto far = sk.predict({5000, 5000, 0}, ws);
  ASSERT_TRUE(far);
  EXPECT_NEAR(far->value, 10, 1e-9);
  EXPECT_NEAR(far->variance, 8.5, 1e-9);
}

TEST(Kriging, SymmetricConfigurationGivesEqualWeightsAndTheMean) {
  PointSet s;
  s.coords = {{-1, 0, 0}, {1, 0, 0}, {0, -1, 0}, {0, 1, 0}};
  s.values = {1, 2, 3, 6};
  for (VariogramType t :
       {VariogramType::kExponential, VariogramType::kGaussian, VariogramType::kSpherical}) {
    const Kriger k = kriger(s, model(t, 0.1, 1, 3));
    KrigingWorkspace ws;
    auto p = k.predict({0, 0, 0}, ws);
    ASSERT_TRUE(p);
    EXPECT_NEAR(p->value, 3.0, 1e-12);
    for (double w : ws.weights) EXPECT_NEAR(w, 0.25, 1e-12);
    // Mirror images of the query get mirrored weights, hence equal variances.
    auto a = k.predict({0.3, 0.2, 0}, ws);
    auto b = k.predict({-0.3, 0.2, 0}, ws);
    ASSERT_TRUE(a && b);
    EXPECT_NEAR(a->variance, b->variance, 1e-12);
  }
}

TEST(Kriging, LocalEqualsGlobalWhenTheNeighbourhoodHoldsEverySample) {
  const PointSet s = randomPoints(40, 8, 100, 3);
  const Kriger global = kriger(s, model(VariogramType::kSpherical, 0.2, 5, 60));
  const Kriger local =
      kriger(s, model(VariogramType::kSpherical, 0.2, 5, 60), {.maxNeighbours = 40});
  KrigingWorkspace wg, wl;
  for (const Point3& q : {Point3{10, 20, 30}, Point3{77, 3, 50}}) {
    auto g = global.predict(q, wg);
    auto l = local.predict(q, wl);
    ASSERT_TRUE(g && l);
    EXPECT_NEAR(g->value, l->value, 1e-10);
    EXPECT_NEAR(g->variance, l->variance, 1e-10);
  }
}

TEST(Kriging, ReducesToTheTextbookSinglePointAnswer) {
  PointSet s;
  s.coords = {{0, 0, 0}};
  s.values = {4.5};
  const Variogram v = model(VariogramType::kExponential, 0, 2, 30);
  const Kriger k = kriger(s, v);
  KrigingWorkspace ws;
  auto p = k.predict({10, 0, 0}, ws);
  ASSERT_TRUE(p);
  EXPECT_DOUBLE_EQ(p->value, 4.5);
  EXPECT_NEAR(p->variance, 2 * v.gamma(10), 1e-12);  // ordinary kriging: 2 gamma(h)
  EXPECT_EQ(p->neighbours, 1u);
}

}  // namespace
}  // namespace voxlink::geostat
