// SPDX-License-Identifier: BSD-3-Clause
// A perspective pinhole camera orbiting a target. Both renderers build primary rays from the
// same numbers (primaryRay), the GL one in float, the reference in double.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <optional>
#include <string>

#include "base/error.h"

namespace voxlink::render {

struct Ray {
  glm::dvec3 origin;
  glm::dvec3 direction;  // unit length
};

struct Box {
  glm::dvec3 lo, hi;
  glm::dvec3 center() const { return 0.5 * (lo + hi); }
  double radius() const { return 0.5 * glm::length(hi - lo); }
};

// The world axis shown pointing up; the negative ones suit volumes whose slices run downwards.
enum class UpAxis { kY, kZ, kNegY, kNegZ };
std::optional<UpAxis> parseUpAxis(const std::string& text);  // "y", "z", "-y", "-z"

// Where a camera looks from, as a user types it: "--camera AZ,EL[,DIST[,FOV]]".
struct CameraSpec {
  double azimuthDeg = 30.0;    // about the up axis; 0 looks along +y (z up) or -z (y up)
  double elevationDeg = 20.0;  // above the plane normal to the up axis
  double distanceScale = 1.0;  // 1 frames the bounding sphere exactly
  double fovYDeg = 30.0;
  UpAxis up = UpAxis::kZ;
};

Result<CameraSpec> parseCameraSpec(const std::string& text, CameraSpec defaults = {});

class Camera {
 public:
  // Looks at the box's centre from the spec's direction, far enough to see all of it.
  static Camera framing(const Box& box, const CameraSpec& spec);
  // A camera at `eye` looking at `target`; `up` must not be parallel to the view direction
  // (checked: VOXLINK_CHECK).
  static Camera lookAt(const glm::dvec3& eye, const glm::dvec3& target, const glm::dvec3& up,
                       double fovYDeg);

  glm::dvec3 eye() const { return target_ + distance_ * back(); }
  glm::dvec3 right() const { return orientation_[0]; }
  glm::dvec3 up() const { return orientation_[1]; }
  glm::dvec3 back() const { return orientation_[2]; }  // from target towards the eye
  const glm::dvec3& target() const { return target_; }
  double distance() const { return distance_; }
  double fovYDeg() const { return fovYDeg_; }

  // The ray through pixel (px, py) of a width x height image, pixel centres at +0.5, row 0 at
  // the top.
  Ray primaryRay(uint32_t px, uint32_t py, uint32_t width, uint32_t height) const;
  // Half extents of the image plane at distance 1 (tan of the half angles).
  glm::dvec2 planeHalfExtent(uint32_t width, uint32_t height) const;

  // Turns the camera about the target: yaw about the world up axis, pitch about its right axis.
  void orbit(double yawDeg, double pitchDeg);
  // Rotates the camera about the target around a world axis (the benchmark's turns).
  void rotateAboutWorldAxis(const glm::dvec3& axis, double degrees);
  // Moves target and eye in the image plane by fractions of the view height.
  void pan(double dx, double dy);
  // Divides the distance to the target by `factor` (> 1 moves closer).
  void zoom(double factor);
  // Converts a camera-space direction (light) into world space.
  glm::dvec3 toWorld(const glm::dvec3& cameraSpace) const { return orientation_ * cameraSpace; }

 private:
  void reorthonormalize();

  glm::dvec3 target_{0.0};
  double distance_ = 1.0;
  glm::dmat3 orientation_{1.0};  // columns: right, up, back
  glm::dvec3 worldUp_{0.0, 0.0, 1.0};
  double fovYDeg_ = 30.0;
};

}  // namespace voxlink::render
