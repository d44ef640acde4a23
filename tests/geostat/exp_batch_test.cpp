// SPDX-License-Identifier: BSD-3-Clause
#include "geostat/detail/exp_batch.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

namespace voxlink::geostat {
namespace {

// expBatch equals std::exp bit for bit on a million random arguments where local kriging
// calls it (-3 h / range) and on the edges of glibc's fast path, special values included.
TEST(ExpBatch, EqualsStdExpBitForBit) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> near(-45, 5), wide(-750, 750);
  std::vector<double> x;
  for (int i = 0; i < 1000000; ++i) x.push_back(i % 8 == 7 ? wide(rng) : near(rng));
  for (double edge : {0x1p-54, 0x1p-55, 0x1.fffffffffffffp-55, 511.9999, 512.0, 709.78, 709.79,
                      -708.39, -745.2, -745.1, 0.0, -0.0, 1e-300})
    for (double sign : {1.0, -1.0}) x.push_back(sign * edge);
  x.push_back(std::numeric_limits<double>::infinity());
  x.push_back(-std::numeric_limits<double>::infinity());
  x.push_back(std::numeric_limits<double>::quiet_NaN());
  std::vector<double> out(x.size());
  expBatch(x.data(), out.data(), x.size());
  size_t differing = 0;
  for (size_t i = 0; i < x.size(); ++i) {
    const double expected = std::exp(x[i]);
    if (std::memcmp(&expected, &out[i], sizeof expected) != 0 &&
        !(std::isnan(expected) && std::isnan(out[i])))
      ++differing;
  }
  EXPECT_EQ(differing, 0u) << "of " << x.size();
}

#if defined(__x86_64__) && defined(__GLIBC__) && \
    (__GLIBC__ > 2 || (__GLIBC__ == 2 && __GLIBC_MINOR__ >= 28))
// On x86-64 with AVX2 + FMA and glibc 2.28 or later the vector path must be the one taken
// (else the check above compares std::exp with itself).
TEST(ExpBatch, VectorizedWhereGlibcsFmaExpRuns) {
  if (!__builtin_cpu_supports("avx2") || !__builtin_cpu_supports("fma"))
    GTEST_SKIP() << "no AVX2 + FMA";
  EXPECT_TRUE(expBatchIsVectorized());
}
#endif

}  // namespace
}  // namespace voxlink::geostat
