// SPDX-License-Identifier: BSD-3-Clause
// Dragging an object (viewer/app/detail/object_drag.h): the point under the cursor stays under
// it, checked against the camera's own primary rays, and the clamp into the grid.
#include "viewer/app/detail/object_drag.h"

#include <gtest/gtest.h>

namespace voxlink::viewer {
namespace {

// Distance from `p` to the primary ray through pixel (px, py).
double distanceToRay(const Camera& camera, uint32_t px, uint32_t py, uint32_t w, uint32_t h,
                     const glm::dvec3& p) {
  const render::Ray ray = camera.primaryRay(px, py, w, h);
  const glm::dvec3 d = p - ray.origin;
  return glm::length(d - glm::dot(d, ray.direction) * ray.direction);
}

TEST(ObjectDrag, ThePointUnderTheCursorStaysUnderIt) {
  render::CameraSpec spec;
  spec.azimuthDeg = 40;
  spec.elevationDeg = 25;
  spec.fovYDeg = 35;
  const Camera camera = Camera::framing({glm::dvec3(-1, -2, 0), glm::dvec3(3, 1, 2)}, spec);
  const uint32_t w = 640, h = 480;
  for (const auto& [px, py, dx, dy] : std::vector<std::array<int, 4>>{
           {320, 240, 37, -12}, {50, 400, 200, -300}, {600, 20, -1, 0}}) {
    const render::Ray ray = camera.primaryRay(px, py, w, h);
    for (double t : {2.0, camera.distance(), 3 * camera.distance()}) {
      const glm::dvec3 p = ray.origin + t * ray.direction;
      auto move = viewPlaneTranslation(camera, p, dx, dy, h);
      ASSERT_TRUE(move) << move.message();
      const glm::dvec3 moved = p + *move;
      EXPECT_NEAR(distanceToRay(camera, px + dx, py + dy, w, h, moved), 0, 1e-9 * t);
      // In the view plane: the depth did not change.
      EXPECT_NEAR(glm::dot(*move, camera.back()), 0, 1e-12 * t);
    }
  }
}

TEST(ObjectDrag, FartherObjectsMoveMoreWorldUnitsPerPixel) {
  const Camera camera = Camera::lookAt({0, 0, 10}, {0, 0, 0}, {0, 1, 0}, 90);
  auto near = viewPlaneTranslation(camera, {0, 0, 9}, 10, 0, 100);  // depth 1
  auto far = viewPlaneTranslation(camera, {0, 0, 6}, 10, 0, 100);   // depth 4
  ASSERT_TRUE(near && far);
  // 90 degrees: the view is 2 x depth high over 100 pixels; x is the camera's right.
  EXPECT_NEAR(near->x, 0.2, 1e-12);
  EXPECT_NEAR(far->x, 0.8, 1e-12);
  auto down = viewPlaneTranslation(camera, {0, 0, 9}, 0, 10, 100);  // cursor down: world down
  ASSERT_TRUE(down);
  EXPECT_NEAR(down->y, -0.2, 1e-12);
}

TEST(ObjectDrag, RefusesPointsBehindTheEyeAndBadViewports) {
  const Camera camera = Camera::lookAt({0, 0, 10}, {0, 0, 0}, {0, 1, 0}, 30);
  EXPECT_FALSE(viewPlaneTranslation(camera, {0, 0, 11}, 1, 1, 100));
  EXPECT_FALSE(viewPlaneTranslation(camera, {0, 0, 10}, 1, 1, 100));
  EXPECT_FALSE(viewPlaneTranslation(camera, {0, 0, 0}, 1, 1, 0));
  EXPECT_FALSE(viewPlaneTranslation(camera, {0, 0, 0}, std::nan(""), 1, 100));
}

TEST(ObjectDrag, ClampsEachAxisIntoTheGridAndSaysWhich) {
  const Box grid{{-0.5, -0.5, -0.5}, {9.5, 9.5, 9.5}};
  const Box object{{2, 3, 4}, {4, 5, 6}};
  auto inside = clampTranslation(object, {1, -2, 3}, grid);
  ASSERT_TRUE(inside) << inside.message();
  EXPECT_EQ(inside->translation, glm::dvec3(1, -2, 3));
  EXPECT_EQ(inside->clamped, (std::array<bool, 3>{false, false, false}));
  auto out = clampTranslation(object, {10, -7, 3.5}, grid);
  ASSERT_TRUE(out) << out.message();
  EXPECT_EQ(out->translation, glm::dvec3(5.5, -3.5, 3.5));  // faces on the grid's faces
  EXPECT_EQ(out->clamped, (std::array<bool, 3>{true, true, false}));
  auto wide = clampTranslation({{-1, 0, 0}, {11, 1, 1}}, {0, 0, 0}, grid);
  ASSERT_FALSE(wide);
  EXPECT_NE(wide.message().find("wider than the grid"), std::string::npos) << wide.message();
}

}  // namespace
}  // namespace voxlink::viewer
