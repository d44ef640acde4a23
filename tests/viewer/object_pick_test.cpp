// SPDX-License-Identifier: BSD-3-Clause
// Which moving object is under a pixel (viewer/app/detail/object_pick.h): the nearest box the
// pixel's primary ray enters.
#include "viewer/app/detail/object_pick.h"

#include <gtest/gtest.h>

namespace voxlink::viewer {
namespace {

using render::Box;
using render::Camera;

TEST(ObjectPick, RayEntersBoxAtItsNearFace) {
  const render::Ray ray{{-5, 0.5, 0.5}, {1, 0, 0}};
  const auto t = rayEntersBox(ray, Box{{0, 0, 0}, {1, 1, 1}});
  ASSERT_TRUE(t);
  EXPECT_DOUBLE_EQ(*t, 5.0);
  EXPECT_FALSE(rayEntersBox(ray, Box{{0, 2, 0}, {1, 3, 1}}));    // beside it, parallel
  EXPECT_FALSE(rayEntersBox(ray, Box{{-9, 0, 0}, {-8, 1, 1}}));  // behind the origin
  const auto inside = rayEntersBox(ray, Box{{-6, 0, 0}, {-4, 1, 1}});
  ASSERT_TRUE(inside);
  EXPECT_DOUBLE_EQ(*inside, 0.0);
}

TEST(ObjectPick, PicksTheNearestBoxUnderThePixel) {
  // Looking down -z at the origin: a near box and a far box both on the central ray, a third
  // to the right.
  const Camera camera = Camera::lookAt({0, 0, 10}, {0, 0, 0}, {0, 1, 0}, 30);
  const std::vector<Box> boxes{{{-1, -1, -4}, {1, 1, -2}},  // far
                               {{-1, -1, 1}, {1, 1, 3}},    // near
                               {{3, -1, -1}, {4, 1, 1}}};   // right
  const uint32_t w = 200, h = 100;
  EXPECT_EQ(pickBox(camera, 100, 50, w, h, boxes), std::optional<size_t>(1));
  // The right box: find its pixel through the camera's own rays (x grows to the right).
  std::optional<size_t> right;
  for (uint32_t x = 100; x < w && !right; ++x)
    if (auto p = pickBox(camera, x, 50, w, h, {boxes[2]})) right = x;
  ASSERT_TRUE(right);
  EXPECT_EQ(pickBox(camera, double(*right), 50, w, h, boxes), std::optional<size_t>(2));
  EXPECT_FALSE(pickBox(camera, 100, 2, w, h, boxes));  // above everything
  EXPECT_FALSE(pickBox(camera, -1, 50, w, h, boxes));  // outside the image
  EXPECT_FALSE(pickBox(camera, 100, 100, w, h, boxes));
  EXPECT_FALSE(pickBox(camera, 100, 50, w, h, {}));
}

}  // namespace
}  // namespace voxlink::viewer
