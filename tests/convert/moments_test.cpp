// SPDX-License-Identifier: BSD-3-Clause
#include "convert/moments.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "tests/convert/volume_fixtures.h"

namespace voxlink::convert {
namespace {

TEST(Moments, StableAroundALargeOffset) {
  // Values 1e6 + small noise: a one-pass sum of squares would lose every digit of sigma.
  auto v = testing::makeVolume<double>({31, 29, 27}, [](uint32_t x, uint32_t y, uint32_t z) {
    return 1e6 + 1e-3 * std::sin(x * 1.3 + y * 0.7 + z * 0.11);
  });
  long double sum = 0;
  const auto* data = reinterpret_cast<const double*>(v->bytes().data());
  const size_t n = v->info().voxelCount();
  for (size_t i = 0; i < n; ++i) sum += data[i];
  const long double mean = sum / n;
  long double m2 = 0;
  for (size_t i = 0; i < n; ++i) m2 += (data[i] - mean) * (data[i] - mean);
  const double sigma = static_cast<double>(std::sqrt(m2 / n));
  for (uint32_t slab : {1u, 5u, 64u}) {
    auto m = measureMoments(*v, slab);
    ASSERT_TRUE(m) << m.message();
    EXPECT_EQ(m->count, n);
    EXPECT_NEAR(m->mean, static_cast<double>(mean), 1e-9);
    EXPECT_NEAR(m->sigma, sigma, sigma * 1e-6);
  }
}

TEST(Moments, ConstantVolumeHasZeroSigmaAndNaNIsRefused) {
  auto c = testing::makeVolume<float>({5, 5, 5}, [](uint32_t, uint32_t, uint32_t) { return 2.5f; });
  auto m = measureMoments(*c);
  ASSERT_TRUE(m);
  EXPECT_EQ(m->sigma, 0.0);
  EXPECT_EQ(m->mean, 2.5);
  auto bad = testing::makeVolume<float>(
      {5, 5, 5}, [](uint32_t x, uint32_t, uint32_t z) { return x == 2 && z == 4 ? NAN : 1.0f; });
  auto e = measureMoments(*bad);
  ASSERT_FALSE(e);
  EXPECT_EQ(e.code(), ErrorCode::kNonFinite);
  EXPECT_NE(e.message().find("(2, 0, 4)"), std::string::npos) << e.message();
}

}  // namespace
}  // namespace voxlink::convert

#include "convert/histogram.h"

namespace voxlink::convert {
namespace {

TEST(Histogram, CountsEveryVoxelAndGivesIntegersTheirOwnBins) {
  auto v = testing::makeVolume<uint8_t>(
      {10, 10, 10}, [](uint32_t x, uint32_t y, uint32_t) { return uint8_t(10 + (x + y) % 5); });
  auto h = measureHistogram(*v, 64);
  ASSERT_TRUE(h) << h.message();
  ASSERT_EQ(h->counts.size(), 5u);  // values 10..14, one bin each
  uint64_t total = 0;
  for (uint64_t c : h->counts) total += c;
  EXPECT_EQ(total, 1000u);
  EXPECT_EQ(h->counts[0], 200u);  // (x + y) % 5 == 0 for a fifth of the voxels
  EXPECT_DOUBLE_EQ(h->quantile(0.5),
                   13.0);  // 60 % of voxels are <= 12, i.e. in bins up to [12, 13)
}

TEST(Histogram, FloatRangeIsSplitEvenly) {
  auto v = testing::makeVolume<float>({100, 1, 1},
                                      [](uint32_t x, uint32_t, uint32_t) { return x * 0.01f; });
  auto h = measureHistogram(*v, 10);
  ASSERT_TRUE(h);
  ASSERT_EQ(h->counts.size(), 10u);
  for (uint64_t c : h->counts) EXPECT_NEAR(double(c), 10.0, 1.0);
}

TEST(MomentsAndHistogram, InactiveVoxelsAreLeftOut) {
  // Values x; only x >= 60 is active, so a background of 0..59 must not move the statistics.
  auto v = testing::makeVolume<float>({100, 3, 2},
                                      [](uint32_t x, uint32_t, uint32_t) { return float(x); });
  testing::PartlyActiveSource masked(*v, [](uint32_t x, uint32_t, uint32_t) { return x >= 60; });
  auto m = measureMoments(masked, 1);
  ASSERT_TRUE(m) << m.message();
  EXPECT_EQ(m->count, 40u * 3 * 2);
  EXPECT_EQ(m->min, 60.0);
  EXPECT_EQ(m->max, 99.0);
  EXPECT_DOUBLE_EQ(m->mean, 79.5);
  EXPECT_NEAR(m->sigma, std::sqrt((40.0 * 40.0 - 1) / 12), 1e-12);
  auto h = measureHistogram(masked, 4);
  ASSERT_TRUE(h) << h.message();
  uint64_t total = 0;
  for (uint64_t c : h->counts) total += c;
  EXPECT_EQ(total, m->count);
}

TEST(MomentsAndHistogram, ProgressRisesSlabBySlabToOne) {
  // 10 slices in slabs of 3: 4 slabs per pass; the histogram's two passes share 0..1.
  auto v = testing::makeVolume<uint8_t>({4, 4, 10},
                                        [](uint32_t x, uint32_t, uint32_t z) { return x + z; });
  std::vector<std::pair<double, std::string>> heard;
  const PassProgress listen = [&](double f, const char* stage) { heard.emplace_back(f, stage); };
  ASSERT_TRUE(measureMoments(*v, 3, listen));
  ASSERT_EQ(heard.size(), 4u);
  EXPECT_DOUBLE_EQ(heard[0].first, 0.3);
  EXPECT_DOUBLE_EQ(heard.back().first, 1.0);
  EXPECT_EQ(heard.back().second, "moments");
  heard.clear();
  ASSERT_TRUE(measureHistogram(*v, 8, 3, listen));
  ASSERT_EQ(heard.size(), 8u);
  for (size_t i = 1; i < heard.size(); ++i) EXPECT_GT(heard[i].first, heard[i - 1].first);
  EXPECT_DOUBLE_EQ(heard[3].first, 0.5);
  EXPECT_EQ(heard[3].second, "moments");
  EXPECT_DOUBLE_EQ(heard.back().first, 1.0);
  EXPECT_EQ(heard.back().second, "histogram");
}

}  // namespace
}  // namespace voxlink::convert
