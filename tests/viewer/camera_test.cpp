// SPDX-License-Identifier: BSD-3-Clause
// Camera framing, primary rays, orbit/pan/zoom.
#include "render/camera.h"

#include <gtest/gtest.h>

#include <cmath>

namespace voxlink::render {

namespace {

const Box kBox{{-1, -2, -3}, {5, 4, 9}};

TEST(Camera, FramingSeesTheWholeBoundingSphere) {
  for (double az : {0.0, 47.0, 180.0, -120.0})
    for (double el : {-60.0, 0.0, 35.0}) {
      CameraSpec spec;
      spec.azimuthDeg = az;
      spec.elevationDeg = el;
      const Camera c = Camera::framing(kBox, spec);
      const glm::dvec3 toCenter = kBox.center() - c.eye();
      // The sphere's angular radius equals half the vertical field of view.
      const double angular = std::asin(kBox.radius() / glm::length(toCenter)) * 180 / M_PI;
      EXPECT_NEAR(angular, spec.fovYDeg / 2, 1e-9);
      EXPECT_NEAR(glm::dot(glm::normalize(toCenter), -c.back()), 1.0, 1e-12);
      EXPECT_NEAR(glm::dot(c.right(), c.up()), 0.0, 1e-12);
    }
}

TEST(Camera, UpAxes) {
  for (auto [text, axis] :
       {std::pair{"z", glm::dvec3(0, 0, 1)}, std::pair{"-z", glm::dvec3(0, 0, -1)},
        std::pair{"y", glm::dvec3(0, 1, 0)}, std::pair{"-y", glm::dvec3(0, -1, 0)}}) {
    CameraSpec spec;
    spec.up = *parseUpAxis(text);
    const Camera c = Camera::framing(kBox, spec);
    EXPECT_GT(glm::dot(c.up(), axis), 0.5) << text;
    EXPECT_NEAR(glm::dot(c.right(), axis), 0.0, 1e-12) << text;
  }
  EXPECT_FALSE(parseUpAxis("x"));
}

TEST(Camera, MiddlePixelOfAnOddImageLooksExactlyAlongTheAxis) {
  const Camera c = Camera::lookAt({0, 0, 10}, {0, 0, 0}, {0, 1, 0}, 40);
  const Ray r = c.primaryRay(16, 15, 33, 31);
  EXPECT_EQ(r.direction.x, 0.0);
  EXPECT_EQ(r.direction.y, 0.0);
  EXPECT_EQ(r.direction.z, -1.0);
  // Row 0 is the top: its rays point up.
  EXPECT_GT(c.primaryRay(16, 0, 33, 31).direction.y, 0.0);
  EXPECT_GT(c.primaryRay(32, 15, 33, 31).direction.x, 0.0);
}

TEST(Camera, OrbitKeepsTheDistanceAndStopsAtThePole) {
  Camera c = Camera::framing(kBox, {});
  const double d = glm::length(c.eye() - c.target());
  c.orbit(33, 20);
  EXPECT_NEAR(glm::length(c.eye() - c.target()), d, 1e-9);
  c.orbit(0, 500);  // far past the pole: clamped below it
  EXPECT_LT(glm::dot(c.back(), glm::dvec3(0, 0, 1)), 1.0);
  EXPECT_GT(glm::dot(c.up(), glm::dvec3(0, 0, 1)), 0.0);
  c.rotateAboutWorldAxis({1, 0, 0}, 360);
  EXPECT_NEAR(glm::length(c.eye() - c.target()), d, 1e-9);
}

TEST(Camera, PanAndZoom) {
  Camera c = Camera::framing(kBox, {});
  const glm::dvec3 t0 = c.target();
  c.pan(0.5, 0);
  EXPECT_LT(glm::dot(c.target() - t0, c.right()), 0.0);  // dragging right moves the scene right
  const double d = c.distance();
  c.zoom(2.0);
  EXPECT_NEAR(c.distance(), d / 2, 1e-12);
  c.zoom(0.0);  // ignored
  c.zoom(NAN);
  EXPECT_NEAR(c.distance(), d / 2, 1e-12);
}

TEST(Camera, ParseSpec) {
  auto s = parseCameraSpec("30,-10,1.5,45");
  ASSERT_TRUE(s);
  EXPECT_EQ(s->azimuthDeg, 30);
  EXPECT_EQ(s->elevationDeg, -10);
  EXPECT_EQ(s->distanceScale, 1.5);
  EXPECT_EQ(s->fovYDeg, 45);
  EXPECT_FALSE(parseCameraSpec("30"));
  EXPECT_FALSE(parseCameraSpec("30,abc"));
  EXPECT_FALSE(parseCameraSpec("30,95"));     // past the pole
  EXPECT_FALSE(parseCameraSpec("30,10,-1"));  // negative distance
  EXPECT_FALSE(parseCameraSpec("30,10,1,180"));
  EXPECT_EQ(parseCameraSpec("1,2,3,4,5").code(), ErrorCode::kInvalidArgument);
}

// 1e-308 is below the normal doubles: stod threw and the message said "not a number".
TEST(Camera, ParseSpecNumbersAtTheEdgesOfDouble) {
  auto s = parseCameraSpec("30,20,1e-308");
  ASSERT_TRUE(s) << s.message();
  EXPECT_EQ(s->distanceScale, 1e-308);
  auto r = parseCameraSpec("30,20,1e-400");
  ASSERT_FALSE(r);
  EXPECT_EQ(r.message(), "--camera: '1e-400' is too close to 0 for a double (rounds to 0)");
  r = parseCameraSpec("30,20,1e400");
  ASSERT_FALSE(r);
  EXPECT_EQ(r.message(), "--camera: '1e400' is beyond the largest double");
  r = parseCameraSpec("30,2x");
  ASSERT_FALSE(r);
  EXPECT_EQ(r.message(), "--camera: '2x' is not a number (expected AZ,EL[,DIST[,FOV]] in degrees)");
}

}  // namespace
}  // namespace voxlink::render
