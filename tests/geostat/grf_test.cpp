// SPDX-License-Identifier: BSD-3-Clause
// Random fields: the empirical mean, variance and axis variograms must match the model within
// tolerances derived from the sample size and the model's own correlation (a correlated
// field's statistics fluctuate far more than N independent draws would).
#include "geostat/grf.h"

#include <gtest/gtest.h>

#include <cmath>

#include "geostat/field_statistics.h"

namespace voxlink::geostat {
namespace {

struct Collected {
  std::vector<double> values;
  GrfReport report;
};

Collected generate(const GrfSpec& spec) {
  Collected c;
  c.values.reserve(uint64_t{spec.dims[0]} * spec.dims[1] * spec.dims[2]);
  auto r = generateGrf(spec, [&](uint32_t, uint32_t count, const double* slab) -> Status {
    c.values.insert(c.values.end(), slab, slab + uint64_t{count} * spec.dims[0] * spec.dims[1]);
    return Status::ok();
  });
  EXPECT_TRUE(r) << r.message();
  if (r) c.report = *r;
  return c;
}

// sum over pairs of voxels (i, j) of f(x_i - x_j) for a grid of dims n: each lattice offset d
// occurs prod(n_a - |d_a|) times.
template <class F>
double pairSum(std::array<uint32_t, 3> n, F f) {
  double total = 0;
  for (int64_t dz = -int64_t(n[2]) + 1; dz < n[2]; ++dz)
    for (int64_t dy = -int64_t(n[1]) + 1; dy < n[1]; ++dy)
      for (int64_t dx = -int64_t(n[0]) + 1; dx < n[0]; ++dx) {
        const double count =
            double(n[0] - std::abs(dx)) * (n[1] - std::abs(dy)) * (n[2] - std::abs(dz));
        total += count * f(dx, dy, dz);
      }
  return total;
}

void checkStatistics(const GrfSpec& spec, const Variogram& v) {
  const Collected c = generate(spec);
  const std::vector<uint32_t> lags{1, 2, 4, 8};
  FieldStatistics stats(spec.dims, lags);
  stats.add(0, spec.dims[2], c.values.data());
  const double n = double(stats.count());
  auto cov = [&](double dx, double dy, double dz) {
    return v.covariance(std::sqrt(dx * dx + dy * dy + dz * dz));
  };
  const double varMean =
      pairSum(spec.dims, [&](double x, double y, double z) { return cov(x, y, z); }) / (n * n);
  const double varVar =
      2 *
      pairSum(spec.dims, [&](double x, double y, double z) { return std::pow(cov(x, y, z), 2); }) /
      (n * n);
  EXPECT_NEAR(stats.mean(), spec.mean, 5 * std::sqrt(varMean)) << v.describe();
  // E[sample variance] = sill - Var(mean).
  EXPECT_NEAR(stats.sigma() * stats.sigma(), v.sill() - varMean, 5 * std::sqrt(varVar))
      << v.describe();
  for (int axis = 0; axis < 3; ++axis) {
    if (spec.dims[axis] == 1) continue;
    for (size_t l = 0; l < lags.size(); ++l) {
      const double h = lags[l];
      // Increments D = Z(x + h e) - Z(x) have covariance 2C(d) - C(d + h e) - C(d - h e);
      // Var(mean D^2 / 2) = sum over pairs of Cov_D^2 / (2 M^2).
      std::array<uint32_t, 3> m = spec.dims;
      m[axis] -= lags[l];
      const double pairs = double(m[0]) * m[1] * m[2];
      auto shifted = [&](double x, double y, double z, double s) {
        double d[3] = {x, y, z};
        d[axis] += s;
        return cov(d[0], d[1], d[2]);
      };
      const double var =
          pairSum(m,
                  [&](double x, double y, double z) {
                    const double cd = 2 * cov(x, y, z) - shifted(x, y, z, h) - shifted(x, y, z, -h);
                    return cd * cd;
                  }) /
          (2 * pairs * pairs);
      EXPECT_NEAR(stats.gamma(axis, l), v.gamma(h), 5 * std::sqrt(var) + 1e-3 * v.sill())
          << v.describe() << " axis " << axis << " lag " << h;
    }
  }
}

TEST(RandomField, StatisticsMatchEachModelWithinSampleSizeTolerances) {
  const VariogramParams models[] = {
      {VariogramType::kExponential, 0, 1, 8, 0.5},
      {VariogramType::kSpherical, 0.1, 0.9, 10, 0.5},
      {VariogramType::kGaussian, 0, 1, 8, 0.5},
      {VariogramType::kMatern, 0, 1, 9, 1.5},
  };
  for (const VariogramParams& p : models) {
    GrfSpec spec;
    spec.dims = {40, 40, 40};
    spec.model = p;
    spec.seed = 1234;
    spec.threads = 2;
    checkStatistics(spec, Variogram::make(p).value());
  }
}

TEST(RandomField, TwoDimensionalFieldsUseTheTwoDimensionalKernel) {
  GrfSpec spec;
  spec.dims = {160, 160, 1};
  spec.model = {VariogramType::kExponential, 0, 2, 10, 0.5};
  spec.mean = 5;
  spec.seed = 99;
  checkStatistics(spec, Variogram::make(spec.model).value());
}

TEST(RandomField, DoesNotDependOnBlockSizeOrThreadsAndDependsOnTheSeed) {
  GrfSpec spec;
  spec.dims = {45, 38, 29};
  spec.model = {VariogramType::kExponential, 0, 1, 6, 0.5};
  spec.seed = 7;
  spec.threads = 1;
  const Collected big = generate(spec);
  spec.fftSize = 32;  // several blocks per axis
  spec.threads = 2;
  const Collected small = generate(spec);
  ASSERT_GT(small.report.blocks, big.report.blocks);
  ASSERT_EQ(big.values.size(), small.values.size());
  double maxDiff = 0;
  for (size_t i = 0; i < big.values.size(); ++i)
    maxDiff = std::max(maxDiff, std::fabs(big.values[i] - small.values[i]));
  EXPECT_LT(maxDiff, 1e-12);
  spec.seed = 8;
  const Collected other = generate(spec);
  double diff = 0;
  for (size_t i = 0; i < big.values.size(); ++i) diff += std::fabs(big.values[i] - other.values[i]);
  EXPECT_GT(diff / big.values.size(), 0.5);
}

// Blocks that do not all fit in memory run on fewer threads (the same field); a block that does
// not fit alone is refused before any is allocated, naming the range.
TEST(RandomField, FitsItsThreadsToTheMemoryAndRefusesWhatCannotFit) {
  GrfSpec spec;
  spec.dims = {45, 38, 29};
  spec.model = {VariogramType::kExponential, 0, 1, 6, 0.5};
  spec.seed = 7;
  spec.threads = 2;
  spec.fftSize = 32;
  const Collected two = generate(spec);
  ASSERT_EQ(two.report.threads, 2u);
  // 32^3 in place: 17 x 32 x 32 complex values per block, 278,528 bytes.
  const uint64_t block = uint64_t{17} * 32 * 32 * 16;
  // Room for the output slab, the kernel's spectrum, the kernel and one and a half blocks.
  const uint64_t slab = uint64_t{45} * 38 * two.report.blockSize[2] * sizeof(double);
  const uint64_t spectrum = uint64_t{17} * 32 * 32 * sizeof(double);
  const uint64_t side = two.report.kernel.side();
  spec.memoryBytes = slab + spectrum + side * side * side * sizeof(double) + block + block / 2;
  const Collected one = generate(spec);
  EXPECT_EQ(one.report.threads, 1u);
  EXPECT_EQ(one.values, two.values);
  spec.memoryBytes = block;
  auto refused = generateGrf(spec, [](uint32_t, uint32_t, const double*) { return Status::ok(); });
  ASSERT_FALSE(refused);
  EXPECT_EQ(refused.code(), ErrorCode::kTooLarge);
  EXPECT_NE(refused.message().find("random field: range 6 voxels needs FFT blocks of 32 x 32 x 32"),
            std::string::npos)
      << refused.message();
}

TEST(RandomField, ReportsKernelDiagnosticsAndRefusesBadSpecs) {
  GrfSpec spec;
  spec.dims = {32, 32, 32};
  spec.model = {VariogramType::kSpherical, 0, 1, 12, 0.5};
  const Collected c = generate(spec);
  // The symmetric square root of the spherical model is not compact (the ball's transform
  // changes sign; its square root cannot): the kernel reaches past range / 2.
  EXPECT_GT(c.report.kernel.radius, 6u);
  EXPECT_LT(c.report.kernel.radius, c.report.kernel.embeddingHalfSize);
  EXPECT_LE(c.report.kernel.truncatedEnergy, spec.kernel.tolerance);
  // Exponential: energy of exp(-3r/a)/r beyond R is exp(-6R/a), so R ~ 1.5 a for 1e-4.
  spec.model = {VariogramType::kExponential, 0, 1, 12, 0.5};
  const Collected e = generate(spec);
  EXPECT_GE(e.report.kernel.radius, 12u);
  EXPECT_LE(e.report.kernel.radius, 20u);
  EXPECT_LE(e.report.kernel.truncatedEnergy, spec.kernel.tolerance);
  spec.model = {VariogramType::kSpherical, 0, 1, 12, 0.5};
  EXPECT_LT(c.report.kernel.negativeEigenvalueMass, 1e-3);
  spec.dims = {0, 4, 4};
  auto bad = generateGrf(spec, [](uint32_t, uint32_t, const double*) { return Status::ok(); });
  ASSERT_FALSE(bad);
  EXPECT_EQ(bad.code(), ErrorCode::kInvalidArgument);
  EXPECT_NE(bad.message().find("dims"), std::string::npos);
  spec.dims = {8, 8, 8};
  auto failingSink = generateGrf(spec, [](uint32_t, uint32_t, const double*) -> Status {
    return makeError(ErrorCode::kIo, "sink.raw: disk full");
  });
  ASSERT_FALSE(failingSink);
  EXPECT_EQ(failingSink.code(), ErrorCode::kIo);
}

TEST(RandomField, LatticeNoiseIsStandardNormal) {
  double sum = 0, sumSq = 0, outside = 0;
  const int n = 400000;
  for (int i = 0; i < n; ++i) {
    const double z = latticeNoise(3, i % 97 - 40, i / 97, -5);
    sum += z;
    sumSq += z * z;
    outside += std::fabs(z) > 1.959963985;
  }
  EXPECT_NEAR(sum / n, 0, 5 / std::sqrt(n));
  EXPECT_NEAR(sumSq / n, 1, 5 * std::sqrt(2.0 / n));
  EXPECT_NEAR(outside / n, 0.05, 5 * std::sqrt(0.05 * 0.95 / n));
}

}  // namespace
}  // namespace voxlink::geostat
