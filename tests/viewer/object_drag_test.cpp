// SPDX-License-Identifier: BSD-3-Clause
// Dragging an object (viewer/app/detail/object_drag.h): the point under the cursor stays under
// it, checked against the camera's own primary rays, and the clamp into the grid.
#include "viewer/app/detail/object_drag.h"

#include <gtest/gtest.h>

#include <cmath>

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

namespace voxlink::viewer {
namespace {

// A drag as the viewer applies it: the box's centre follows the cursor at its depth, the pose's
// rotation is kept, and the translation stops at the grid's faces.
TEST(ObjectDrag, DragPoseFollowsTheCursorAndStopsAtTheGrid) {
  const Camera camera = Camera::lookAt({0, 0, 20}, {0, 0, 0}, {0, 1, 0}, 30);
  scene::Pose start;
  start.translate = {1, 0, 0};
  start.rotateDegrees = {0, 30, 0};
  const Box box{{0, -1, -1}, {2, 1, 1}};  // the object's box at `start`
  const Box grid{{-10, -10, -10}, {10, 10, 10}};
  const double h = 400;
  auto small = dragPose(camera, start, box, grid, 10, -20, h);
  ASSERT_TRUE(small) << small.message();
  auto expected = viewPlaneTranslation(camera, box.center(), 10, -20, h);
  ASSERT_TRUE(expected);
  for (int a = 0; a < 3; ++a)
    EXPECT_DOUBLE_EQ(small->pose.translate[size_t(a)], start.translate[size_t(a)] + (*expected)[a]);
  EXPECT_EQ(small->pose.rotateDegrees, start.rotateDegrees);
  EXPECT_EQ(small->clamped, (std::array<bool, 3>{false, false, false}));
  EXPECT_GT(small->pose.translate[0], start.translate[0]);  // right on screen is +x here
  EXPECT_GT(small->pose.translate[1], 0.0);                 // up on screen (dy < 0) is +y

  // Far to the right: the box's right face stops at the grid's (x 2 + t = 10).
  auto far = dragPose(camera, start, box, grid, 1e5, 0, h);
  ASSERT_TRUE(far) << far.message();
  EXPECT_EQ(far->clamped, (std::array<bool, 3>{true, false, false}));
  EXPECT_DOUBLE_EQ(far->pose.translate[0], start.translate[0] + 8);
  EXPECT_FALSE(dragPose(camera, start, box, grid, std::nan(""), 0, h));
  EXPECT_FALSE(dragPose(camera, start, Box{{-30, 0, 0}, {30, 1, 1}}, grid, 1, 0, h));
}

}  // namespace
}  // namespace voxlink::viewer
