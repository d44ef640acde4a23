// SPDX-License-Identifier: BSD-3-Clause
// The viewer's camera controller: mouse input mapped onto the camera's orbit, pan and zoom.
#include "viewer/app/detail/camera_controller.h"

#include <gtest/gtest.h>

#include <cmath>

namespace voxlink::viewer {
namespace {

const render::Box kBox{{-1, -2, -3}, {5, 4, 9}};

TEST(CameraController, DragOrbitsWheelZoomsResetReturnsHome) {
  const render::Camera home = render::Camera::framing(kBox, {});
  CameraController cc(home);
  InputFrame in;
  in.mouseX = 100;
  in.mouseY = 100;
  EXPECT_FALSE(cc.update(in, 600));
  in.left = true;
  EXPECT_FALSE(cc.update(in, 600));  // the press itself does not move
  EXPECT_TRUE(cc.dragging());
  in.mouseX = 150;
  EXPECT_TRUE(cc.update(in, 600));
  EXPECT_GT(glm::length(cc.camera().back() - home.back()), 0.1);
  in.left = false;
  cc.update(in, 600);
  EXPECT_FALSE(cc.dragging());
  in.scroll = 2;
  EXPECT_TRUE(cc.update(in, 600));
  EXPECT_LT(cc.camera().distance(), home.distance());
  in = InputFrame{};
  in.reset = true;
  EXPECT_TRUE(cc.update(in, 600));
  EXPECT_EQ(cc.camera().eye(), home.eye());
}

}  // namespace
}  // namespace voxlink::viewer
