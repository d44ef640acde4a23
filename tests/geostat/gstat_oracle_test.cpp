// SPDX-License-Identifier: BSD-3-Clause
// R's gstat as an independent oracle: the same samples, variogram and neighbourhood must give
// the same predictions and kriging variances (and the same experimental variogram). Skipped
// when Rscript or gstat is missing (scripts/install-deps.sh installs r-cran-gstat).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "geostat/cross_validation.h"
#include "geostat/krige_grid.h"
#include "geostat/variogram_fit.h"
#include "tests/geostat/walker_lake_data.h"

namespace voxlink::geostat {
namespace {

// Relative tolerances: both sides solve the same double-precision systems.
constexpr double kPredictionTolerance = 1e-10;  // times the sample standard deviation
constexpr double kVarianceTolerance = 1e-10;    // times the sill

// Every digit of a double, for the command line.
std::string full(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

bool haveGstat() {
  return std::system(
             "Rscript -e 'suppressPackageStartupMessages(library(gstat))' >/dev/null 2>&1") == 0;
}

struct Table {
  std::vector<Point3> at;
  std::vector<double> pred, var;
};

Table readTable(const std::string& path) {
  Table t;
  const PointSet p = readPoints(path, {"x", "y", "", "pred"}).value();
  const PointSet v = readPoints(path, {"x", "y", "", "var"}).value();
  t.at = p.coords;
  t.pred = p.values;
  t.var = v.values;
  return t;
}

struct Case {
  const char* name;
  VariogramParams params;
  size_t neighbours;
  int stride;
};

std::string gstatModel(const Variogram& v, double& gstatRange) {
  const VariogramParams& p = v.params();
  switch (p.type) {
    case VariogramType::kExponential:
      gstatRange = p.range / 3;
      return "Exp";
    case VariogramType::kSpherical:
      gstatRange = p.range;
      return "Sph";
    case VariogramType::kGaussian:
      gstatRange = p.range / std::sqrt(3.0);
      return "Gau";
    case VariogramType::kMatern:
      gstatRange = v.maternScale();
      return "Mat";
  }
  return "";
}

class GstatOracle : public ::testing::TestWithParam<Case> {};

TEST_P(GstatOracle, PredictionsVariancesAndCrossValidationAgree) {
  VOXLINK_REQUIRE_DATA(test::kWalkerSamples);
  if (!haveGstat())
    GTEST_SKIP() << "Rscript with gstat not installed (apt-get install r-cran-gstat)";
  const Case& c = GetParam();
  const Variogram v = Variogram::make(c.params).value();
  double gstatRange = 0;
  const std::string model = gstatModel(v, gstatRange);
  testing::TempDir dir;
  const std::string command =
      cat("Rscript ", VOXLINK_GSTAT_ORACLE_SCRIPT, " ", testing::dataPath(test::kWalkerSamples),
          " V ", dir.path().string(), " ", model, " ", full(c.params.nugget), " ",
          full(c.params.psill), " ", full(gstatRange), " ", c.params.smoothness, " ", c.neighbours,
          " ", c.stride, " > ", dir.file("log.txt"), " 2>&1");
  ASSERT_EQ(std::system(command.c_str()), 0) << command;

  const PointSet samples = test::walkerSamples();
  double mean = 0, sd = 0;
  for (double s : samples.values) mean += s / double(samples.size());
  for (double s : samples.values) sd += (s - mean) * (s - mean) / double(samples.size());
  sd = std::sqrt(sd);
  const Kriger k = Kriger::make(samples, v, {.maxNeighbours = c.neighbours}).value();
  KrigingWorkspace ws;
  const Table grid = readTable(dir.file("grid.csv"));
  ASSERT_GT(grid.at.size(), 3000u);
  size_t ties = 0, compared = 0;
  double worstPred = 0, worstVar = 0;
  for (size_t i = 0; i < grid.at.size(); ++i) {
    auto p = k.predict(grid.at[i], ws);
    ASSERT_TRUE(p) << p.message();
    if (p->tieAtCutoff) {
      ++ties;
      continue;
    }  // either neighbour set is right
    ++compared;
    worstPred = std::max(worstPred, std::fabs(p->value - grid.pred[i]) / sd);
    worstVar = std::max(worstVar, std::fabs(p->variance - grid.var[i]) / v.sill());
  }
  EXPECT_LE(worstPred, kPredictionTolerance) << c.name;
  EXPECT_LE(worstVar, kVarianceTolerance) << c.name;
  EXPECT_LT(ties, grid.at.size() / 5) << c.name;
  std::printf(
      "[ gstat    ] %s: %zu nodes compared (%zu with a distance tie at the k-th neighbour "
      "skipped), "
      "max |dpred|/sd %.2e, max |dvar|/sill %.2e\n",
      c.name, compared, ties, worstPred, worstVar);

  // Leave-one-out, sample by sample.
  const Table cv = readTable(dir.file("cv.csv"));
  ASSERT_EQ(cv.at.size(), samples.size());
  auto ours = leaveOneOut(k);
  ASSERT_TRUE(ours);
  size_t cvCompared = 0;
  double cvWorst = 0;
  for (size_t i = 0; i < cv.at.size(); ++i) {
    ASSERT_EQ(k.sample(i), cv.at[i]);  // same order: no sample was merged
    if (c.neighbours > 0) {            // global kriging has no neighbour ties
      auto p = k.predict(k.sample(i), ws, int64_t(i));
      ASSERT_TRUE(p);
      if (p->tieAtCutoff) continue;
    }
    ++cvCompared;
    cvWorst = std::max(cvWorst, std::fabs(ours->predicted[i] - cv.pred[i]) / sd);
    EXPECT_NEAR(ours->variance[i], cv.var[i], kVarianceTolerance * v.sill()) << i;
  }
  EXPECT_LE(cvWorst, kPredictionTolerance) << c.name;
  EXPECT_GT(cvCompared, samples.size() * 4 / 5);
}

TEST(GstatOracleVariogram, ExperimentalVariogramAndFitAgree) {
  VOXLINK_REQUIRE_DATA(test::kWalkerSamples);
  if (!haveGstat()) GTEST_SKIP() << "Rscript with gstat not installed";
  testing::TempDir dir;
  const std::string command =
      cat("Rscript ", VOXLINK_GSTAT_ORACLE_SCRIPT, " ", testing::dataPath(test::kWalkerSamples),
          " V ", dir.path().string(), " Sph 0 1 30 0.5 8 20 > ", dir.file("log.txt"), " 2>&1");
  ASSERT_EQ(std::system(command.c_str()), 0);
  const PointSet samples = test::walkerSamples();
  auto bins = experimentalVariogram(samples);
  ASSERT_TRUE(bins);
  const PointSet gamma = readPoints(dir.file("bins.csv"), {"dist", "np", "", "gamma"}).value();
  ASSERT_EQ(gamma.size(), bins->size());
  for (size_t i = 0; i < bins->size(); ++i) {
    EXPECT_EQ((*bins)[i].pairs, uint64_t(gamma.coords[i][1])) << i;
    EXPECT_NEAR((*bins)[i].lag, gamma.coords[i][0], 1e-9 * gamma.coords[i][0]) << i;
    EXPECT_NEAR((*bins)[i].gamma, gamma.values[i], 1e-9 * gamma.values[i]) << i;
  }
  // gstat fits from a generic start by Gauss-Newton; ours scans the range: same optimum.
  auto fit = fitVariogram(*bins, {VariogramType::kSpherical});
  ASSERT_TRUE(fit);
  const PointSet psill = readPoints(dir.file("fit.csv"), {"psill", "range", "", "psill"}).value();
  ASSERT_EQ(psill.size(), 2u);  // rows: Nug, Sph
  EXPECT_NEAR(fit->nugget, psill.values[0], 1e-3 * fit->psill);
  EXPECT_NEAR(fit->psill, psill.values[1], 1e-3 * fit->psill);
  EXPECT_NEAR(fit->range, psill.coords[1][1], 1e-3 * fit->range);
}

// Universal kriging and kriging with external drift against gstat's krige(V ~ X + Y),
// krige(V ~ X + Y + I(X^2) + I(X*Y) + I(Y^2)) and krige(V ~ U) (U known on the grid from the
// exhaustive file): point by point, through the grid solvers, and leave-one-out.
struct DriftCase {
  const char* name;
  DriftKind drift;
  bool external;
  size_t neighbours;
};

constexpr double kDriftTolerance = 1e-8;  // relative, as above; the issue asks for 1e-6

class GstatOracleDrift : public ::testing::TestWithParam<DriftCase> {};

TEST_P(GstatOracleDrift, UniversalKrigingAgreesOnGridPathsAndCrossValidation) {
  VOXLINK_REQUIRE_DATA(test::kWalkerSamples);
  VOXLINK_REQUIRE_DATA(test::kWalkerExhaustive);
  if (!haveGstat()) GTEST_SKIP() << "Rscript with gstat not installed";
  const DriftCase& c = GetParam();
  const VariogramParams params{VariogramType::kSpherical, 22141, 70210, 35.08, 0.5};
  const Variogram v = Variogram::make(params).value();
  const char* trend = c.external                      ? "U"
                      : c.drift == DriftKind::kLinear ? "'X + Y'"
                                                      : "'X + Y + I(X^2) + I(X*Y) + I(Y^2)'";
  testing::TempDir dir;
  const std::string command =
      cat("Rscript ", VOXLINK_GSTAT_ORACLE_SCRIPT, " ", testing::dataPath(test::kWalkerSamples),
          " V ", dir.path().string(), " Sph ", full(params.nugget), " ", full(params.psill), " ",
          full(params.range), " 0.5 ", c.neighbours, " 4 ", trend, " ",
          c.external ? testing::dataPath(test::kWalkerExhaustive) : "", " > ", dir.file("log.txt"),
          " 2>&1");
  ASSERT_EQ(std::system(command.c_str()), 0) << command;

  const PointSet samples = readPoints(testing::dataPath(test::kWalkerSamples),
                                      {"X", "Y", "", "V", c.external ? "U" : ""})
                               .value();
  ASSERT_EQ(samples.size(), c.external ? 275u : 470u);
  const PointSet exhaustiveU =
      readPoints(testing::dataPath(test::kWalkerExhaustive), {"x", "y", "", "U"}).value();
  std::vector<double> nodeU(260 * 300, NAN);
  for (size_t i = 0; i < exhaustiveU.size(); ++i)
    nodeU[size_t(exhaustiveU.coords[i][1] - 1) * 260 + size_t(exhaustiveU.coords[i][0] - 1)] =
        exhaustiveU.values[i];
  double mean = 0, sd = 0;
  for (double s : samples.values) mean += s / double(samples.size());
  for (double s : samples.values) sd += (s - mean) * (s - mean) / double(samples.size());
  sd = std::sqrt(sd);
  const Kriger k =
      Kriger::make(samples, v,
                   {.maxNeighbours = c.neighbours, .drift = c.drift, .externalDrift = c.external})
          .value();
  GridSpec spec;
  spec.dims = {260, 300, 1};
  spec.origin = {1, 1, 0};
  std::vector<double> gridValues, gridVariances;
  GridKrigingOptions gridOptions;
  gridOptions.externalDrift = c.external ? nodeU.data() : nullptr;
  ASSERT_TRUE(krigeGrid(
      k, spec,
      [&](uint32_t, uint32_t count, const double* values, const double* variances) {
        gridValues.insert(gridValues.end(), values, values + count * spec.sliceNodes());
        gridVariances.insert(gridVariances.end(), variances, variances + count * spec.sliceNodes());
        return Status::ok();
      },
      gridOptions));

  const Table grid = readTable(dir.file("grid.csv"));
  ASSERT_GT(grid.at.size(), 4000u);
  KrigingWorkspace ws;
  size_t compared = 0;
  double worstPred = 0, worstVar = 0, worstGrid = 0;
  for (size_t i = 0; i < grid.at.size(); ++i) {
    const size_t node = size_t(grid.at[i][1] - 1) * 260 + size_t(grid.at[i][0] - 1);
    auto p = k.predict(grid.at[i], ws, -1, nodeU[node]);
    ASSERT_TRUE(p) << p.message();
    ASSERT_TRUE(std::isfinite(p->value) && std::isfinite(p->variance));
    worstGrid = std::max({worstGrid, std::fabs(gridValues[node] - p->value) / sd,
                          std::fabs(gridVariances[node] - p->variance) / v.sill()});
    if (p->tieAtCutoff) continue;  // either neighbour set is right
    ++compared;
    worstPred = std::max(worstPred, std::fabs(p->value - grid.pred[i]) / sd);
    worstVar = std::max(worstVar, std::fabs(p->variance - grid.var[i]) / v.sill());
  }
  EXPECT_GT(compared, grid.at.size() * 4 / 5);
  EXPECT_LE(worstPred, kDriftTolerance) << c.name;
  EXPECT_LE(worstVar, kDriftTolerance) << c.name;
  EXPECT_LE(worstGrid, 1e-9) << c.name << ": the grid solver differs from Kriger::predict";

  const Table cv = readTable(dir.file("cv.csv"));
  ASSERT_EQ(cv.at.size(), samples.size());
  auto ours = leaveOneOut(k);
  ASSERT_TRUE(ours) << ours.message();
  double cvWorst = 0;
  size_t cvCompared = 0;
  for (size_t i = 0; i < cv.at.size(); ++i) {
    ASSERT_EQ(k.sample(i), cv.at[i]);
    auto p = k.predict(k.sample(i), ws, int64_t(i), k.sampleExternalDrift(i));
    ASSERT_TRUE(p);
    if (p->tieAtCutoff) continue;
    ++cvCompared;
    cvWorst = std::max({cvWorst, std::fabs(ours->predicted[i] - cv.pred[i]) / sd,
                        std::fabs(ours->variance[i] - cv.var[i]) / v.sill()});
  }
  EXPECT_GT(cvCompared, samples.size() * 4 / 5);
  EXPECT_LE(cvWorst, kDriftTolerance) << c.name;
  std::printf(
      "[ gstat    ] %s: %zu nodes compared, max |dpred|/sd %.2e, max |dvar|/sill %.2e; grid "
      "solver vs point by point %.2e; leave-one-out (%zu samples) %.2e\n",
      c.name, compared, worstPred, worstVar, worstGrid, cvCompared, cvWorst);
}

INSTANTIATE_TEST_SUITE_P(
    WalkerLake, GstatOracleDrift,
    ::testing::Values(DriftCase{"linear_global", DriftKind::kLinear, false, 0},
                      DriftCase{"linear_k16", DriftKind::kLinear, false, 16},
                      DriftCase{"quadratic_k32", DriftKind::kQuadratic, false, 32},
                      DriftCase{"external_u_global", DriftKind::kNone, true, 0},
                      DriftCase{"external_u_k24", DriftKind::kNone, true, 24}),
    [](const ::testing::TestParamInfo<DriftCase>& param) { return std::string(param.param.name); });

INSTANTIATE_TEST_SUITE_P(
    WalkerLake, GstatOracle,
    ::testing::Values(
        Case{"sph_k16", {VariogramType::kSpherical, 22141, 70210, 35.08, 0.5}, 16, 1},
        Case{"exp_global", {VariogramType::kExponential, 15000, 80000, 60, 0.5}, 0, 4},
        Case{"gau_nugget_k24", {VariogramType::kGaussian, 20000, 72000, 30, 0.5}, 24, 4},
        Case{"matern15_k32", {VariogramType::kMatern, 18000, 75000, 45, 1.5}, 32, 4}),
    [](const ::testing::TestParamInfo<Case>& param) { return std::string(param.param.name); });

}  // namespace
}  // namespace voxlink::geostat
