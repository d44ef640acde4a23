// SPDX-License-Identifier: BSD-3-Clause
// Kriging the 470 Walker Lake samples against the exhaustive truth: kriging must beat the
// simple estimators it is meant to beat, and its cross-validation must be consistent with
// its own variance. (The measured numbers are in docs/kriging.md.)
#include <gtest/gtest.h>

#include <cmath>

#include "geostat/cross_validation.h"
#include "geostat/krige_grid.h"
#include "geostat/variogram_fit.h"
#include "tests/geostat/walker_lake_data.h"

namespace voxlink::geostat {
namespace {

struct Errors {
  double rmse = 0, mean = 0;
};

template <class Predict>
Errors compare(const std::vector<double>& truth, Predict predict) {
  Errors e;
  for (uint32_t y = 1; y <= 300; ++y)
    for (uint32_t x = 1; x <= 260; ++x) {
      const double d = predict(x, y) - truth[(y - 1) * 260 + x - 1];
      e.rmse += d * d;
      e.mean += d;
    }
  e.rmse = std::sqrt(e.rmse / 78000);
  e.mean /= 78000;
  return e;
}

TEST(WalkerLake, KrigingBeatsTheMeanAndNearestNeighbourOnTheExhaustiveGrid) {
  VOXLINK_REQUIRE_DATA(test::kWalkerSamples);
  VOXLINK_REQUIRE_DATA(test::kWalkerExhaustive);
  const PointSet samples = test::walkerSamples();
  const std::vector<double> truth = test::walkerExhaustive();
  auto bins = experimentalVariogram(samples);
  ASSERT_TRUE(bins);
  auto params = fitVariogram(*bins, {VariogramType::kSpherical});
  ASSERT_TRUE(params) << params.message();
  const Variogram v = Variogram::make(*params).value();
  const Kriger k = Kriger::make(samples, v, {.maxNeighbours = 16}).value();
  std::vector<double> kriged;
  GridSpec grid{{260, 300, 1}, {1, 1, 0}, {1, 1, 1}};
  auto summary =
      krigeGrid(k, grid, [&](uint32_t, uint32_t, const double* val, const double*) -> Status {
        kriged.assign(val, val + 78000);
        return Status::ok();
      });
  ASSERT_TRUE(summary) << summary.message();
  EXPECT_EQ(summary->regularizedNodes, 0u);
  const Errors krig =
      compare(truth, [&](uint32_t x, uint32_t y) { return kriged[(y - 1) * 260 + x - 1]; });

  double sampleMean = 0;
  for (double s : samples.values) sampleMean += s;
  sampleMean /= double(samples.size());
  const Errors mean = compare(truth, [&](uint32_t, uint32_t) { return sampleMean; });
  const KdTree tree(samples.coords);
  std::vector<Neighbour> nn;
  const Errors nearest = compare(truth, [&](uint32_t x, uint32_t y) {
    tree.nearest({double(x), double(y), 0}, 1, INFINITY, nn);
    return samples.values[nn[0].index];
  });
  EXPECT_LT(krig.rmse, 0.9 * mean.rmse);
  EXPECT_LT(krig.rmse, 0.9 * nearest.rmse);
  // The samples over-represent high values (preferential sampling), so every estimator is
  // biased upward; kriging declusters and is less biased than the raw sample mean.
  EXPECT_LT(std::fabs(krig.mean), std::fabs(mean.mean));
}

TEST(WalkerLake, LeaveOneOutIsConsistentWithTheKrigingVariance) {
  VOXLINK_REQUIRE_DATA(test::kWalkerSamples);
  const PointSet samples = test::walkerSamples();
  auto bins = experimentalVariogram(samples);
  ASSERT_TRUE(bins);
  const Variogram v =
      Variogram::make(fitVariogram(*bins, {VariogramType::kSpherical}).value()).value();
  const Kriger k = Kriger::make(samples, v, {.maxNeighbours = 16}).value();
  auto cv = leaveOneOut(k);
  ASSERT_TRUE(cv) << cv.message();
  EXPECT_EQ(cv->evaluated, 470u);
  double sd = 0, mean = 0;
  for (double s : samples.values) mean += s / 470;
  for (double s : samples.values) sd += (s - mean) * (s - mean) / 470;
  sd = std::sqrt(sd);
  EXPECT_LT(std::fabs(cv->meanError), 0.1 * sd);
  EXPECT_LT(cv->rmse, sd);
  EXPECT_GT(cv->meanStandardizedSquaredError, 0.5);
  EXPECT_LT(cv->meanStandardizedSquaredError, 1.5);
}

}  // namespace
}  // namespace voxlink::geostat
