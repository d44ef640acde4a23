// SPDX-License-Identifier: BSD-3-Clause
// The silhouette/edge measure on small hand-made maps and images.
#include "exact/edge_error.h"

#include <gtest/gtest.h>

#include <cmath>

namespace voxlink::exact {
namespace {

// A 4x4 map: material 0 in the left `split` columns, nothing to the right.
FirstHitMap halves(uint32_t split) {
  FirstHitMap m{4, 4, std::vector<int32_t>(16, kNoHit)};
  for (uint32_t y = 0; y < 4; ++y)
    for (uint32_t x = 0; x < split; ++x) m.material[y * 4 + x] = 0;
  return m;
}

render::Image grey(float v) {
  render::Image image(4, 4);
  for (float& c : image.rgba) c = v;
  return image;
}

TEST(EdgeError, CountsMismatchesAndSeparatesEdgesFromInterior) {
  const FirstHitMap a = halves(2), b = halves(1);
  render::Image test = grey(0.5f), truth = grey(0.5f);
  // The pixels of column 1 differ in colour (one scene covers them, the other does not).
  for (uint32_t y = 0; y < 4; ++y)
    for (int c = 0; c < 3; ++c) test.pixel(1, y)[c] = 0.6f;
  auto e = compareEdges(test, truth, a, b);
  ASSERT_TRUE(e);
  EXPECT_DOUBLE_EQ(e->firstHitMismatch, 4.0 / 16);
  EXPECT_DOUBLE_EQ(e->coverageMismatch, 4.0 / 16);
  // Edges: columns 0 and 1 (b's border), 1 and 2 (a's border).
  EXPECT_DOUBLE_EQ(e->edgeShare, 12.0 / 16);
  EXPECT_NEAR(e->edgePsnr, -10 * std::log10(0.01 * 4 / 12), 1e-4);
  EXPECT_TRUE(std::isinf(e->interiorPsnr));
}

TEST(EdgeError, IdenticalMapsHaveNoMismatch) {
  const FirstHitMap a = halves(2);
  auto e = compareEdges(grey(0.2f), grey(0.2f), a, a);
  ASSERT_TRUE(e);
  EXPECT_EQ(e->firstHitMismatch, 0);
  EXPECT_EQ(e->coverageMismatch, 0);
  EXPECT_FALSE(compareEdges(grey(0.2f), render::Image(2, 2), a, a));
}

}  // namespace
}  // namespace voxlink::exact
