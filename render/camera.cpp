// SPDX-License-Identifier: BSD-3-Clause
#include "render/camera.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <numbers>
#include <sstream>
#include <vector>

#include "base/check.h"

namespace voxlink::render {
namespace {

double radians(double deg) { return deg * std::numbers::pi / 180.0; }

glm::dmat3 rotation(const glm::dvec3& axis, double degrees) {
  const glm::dvec3 a = glm::normalize(axis);
  const double c = std::cos(radians(degrees)), s = std::sin(radians(degrees)), t = 1.0 - c;
  // Rodrigues' formula, column-major.
  return glm::dmat3(t * a.x * a.x + c, t * a.x * a.y + s * a.z, t * a.x * a.z - s * a.y,
                    t * a.x * a.y - s * a.z, t * a.y * a.y + c, t * a.y * a.z + s * a.x,
                    t * a.x * a.z + s * a.y, t * a.y * a.z - s * a.x, t * a.z * a.z + c);
}

}  // namespace

Result<CameraSpec> parseCameraSpec(const std::string& text, CameraSpec spec) {
  std::vector<double> parts;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) {
    // strtod, not stod: stod throws on a number below the normal doubles (1e-308), which was
    // then reported as no number at all.
    const char* begin = item.c_str();
    char* end = nullptr;
    errno = 0;
    const double value = std::strtod(begin, &end);
    if (end == begin || *end != '\0')
      return makeError(ErrorCode::kInvalidArgument, "--camera: '", item,
                       "' is not a number (expected AZ,EL[,DIST[,FOV]] in degrees)");
    if (errno == ERANGE && std::isinf(value))
      return makeError(ErrorCode::kInvalidArgument, "--camera: '", item,
                       "' is beyond the largest double");
    if (errno == ERANGE && value == 0 && item.find_first_not_of("+-0.eE") != std::string::npos)
      return makeError(ErrorCode::kInvalidArgument, "--camera: '", item,
                       "' is too close to 0 for a double (rounds to 0)");
    parts.push_back(value);
  }
  if (parts.size() < 2 || parts.size() > 4)
    return makeError(ErrorCode::kInvalidArgument, "--camera: expected AZ,EL[,DIST[,FOV]], got '",
                     text, "'");
  for (double p : parts)
    if (!std::isfinite(p))
      return makeError(ErrorCode::kInvalidArgument, "--camera: values must be finite, got '", text,
                       "'");
  spec.azimuthDeg = parts[0];
  spec.elevationDeg = parts[1];
  if (parts.size() > 2) spec.distanceScale = parts[2];
  if (parts.size() > 3) spec.fovYDeg = parts[3];
  if (!(spec.distanceScale > 0))
    return makeError(ErrorCode::kInvalidArgument, "--camera: distance ", spec.distanceScale,
                     " must be positive");
  if (!(spec.fovYDeg > 1 && spec.fovYDeg < 170))
    return makeError(ErrorCode::kInvalidArgument, "--camera: field of view ", spec.fovYDeg,
                     " must lie in (1, 170) degrees");
  if (std::abs(spec.elevationDeg) > 89.9)
    return makeError(ErrorCode::kInvalidArgument, "--camera: elevation ", spec.elevationDeg,
                     " must lie in [-89.9, 89.9] degrees");
  return spec;
}

std::optional<UpAxis> parseUpAxis(const std::string& text) {
  if (text == "z") return UpAxis::kZ;
  if (text == "y") return UpAxis::kY;
  if (text == "-z") return UpAxis::kNegZ;
  if (text == "-y") return UpAxis::kNegY;
  return std::nullopt;
}

Camera Camera::framing(const Box& box, const CameraSpec& spec) {
  Camera c;
  c.target_ = box.center();
  c.fovYDeg_ = spec.fovYDeg;
  const double az = radians(spec.azimuthDeg), el = radians(spec.elevationDeg);
  glm::dvec3 back, up;
  if (spec.up == UpAxis::kZ || spec.up == UpAxis::kNegZ) {
    back = {std::sin(az) * std::cos(el), -std::cos(az) * std::cos(el), std::sin(el)};
    up = {0, 0, 1};
  } else {
    back = {std::sin(az) * std::cos(el), std::sin(el), std::cos(az) * std::cos(el)};
    up = {0, 1, 0};
  }
  if (spec.up == UpAxis::kNegZ || spec.up == UpAxis::kNegY) {
    // Half a turn about x: the same view of the volume turned upside down.
    back = {back.x, -back.y, -back.z};
    up = -up;
  }
  c.worldUp_ = up;
  const glm::dvec3 right = glm::normalize(glm::cross(up, back));
  c.orientation_ = glm::dmat3(right, glm::cross(back, right), back);
  const double radius = std::max(box.radius(), 1e-9);
  c.distance_ = spec.distanceScale * radius / std::sin(radians(spec.fovYDeg) / 2);
  return c;
}

Camera Camera::lookAt(const glm::dvec3& eye, const glm::dvec3& target, const glm::dvec3& up,
                      double fovYDeg) {
  VOXLINK_CHECK(eye != target, "a camera needs a view direction");
  VOXLINK_CHECK_GT(glm::length(glm::cross(up, glm::normalize(eye - target))), 1e-9);
  VOXLINK_CHECK(fovYDeg > 0 && fovYDeg < 180, "the field of view is an angle in (0, 180)");
  Camera c;
  c.target_ = target;
  c.fovYDeg_ = fovYDeg;
  c.distance_ = glm::length(eye - target);
  const glm::dvec3 back = glm::normalize(eye - target);
  const glm::dvec3 right = glm::normalize(glm::cross(up, back));
  c.orientation_ = glm::dmat3(right, glm::cross(back, right), back);
  c.worldUp_ = glm::normalize(up);
  return c;
}

glm::dvec2 Camera::planeHalfExtent(uint32_t width, uint32_t height) const {
  const double halfY = std::tan(radians(fovYDeg_) / 2);
  return {halfY * double(width) / double(height), halfY};
}

Ray Camera::primaryRay(uint32_t px, uint32_t py, uint32_t width, uint32_t height) const {
  const glm::dvec2 half = planeHalfExtent(width, height);
  const double sx = (2.0 * (px + 0.5) / width - 1.0) * half.x;
  const double sy = (1.0 - 2.0 * (py + 0.5) / height) * half.y;
  const glm::dvec3 dir = -back() + sx * right() + sy * up();
  return Ray{eye(), glm::normalize(dir)};
}

void Camera::orbit(double yawDeg, double pitchDeg) {
  orientation_ = rotation(worldUp_, yawDeg) * orientation_;
  // Keep the view from flipping over the pole.
  const double elevation =
      std::asin(std::clamp(glm::dot(back(), worldUp_), -1.0, 1.0)) * 180 / std::numbers::pi;
  const double limited = std::clamp(elevation + pitchDeg, -89.0, 89.0);
  orientation_ = rotation(right(), -(limited - elevation)) * orientation_;
  reorthonormalize();
}

void Camera::rotateAboutWorldAxis(const glm::dvec3& axis, double degrees) {
  orientation_ = rotation(axis, degrees) * orientation_;
  reorthonormalize();
}

void Camera::pan(double dx, double dy) {
  const double scale = 2.0 * distance_ * std::tan(radians(fovYDeg_) / 2);
  target_ += (-dx * right() + dy * up()) * scale;
}

void Camera::zoom(double factor) {
  if (factor > 0 && std::isfinite(factor)) distance_ = std::max(distance_ / factor, 1e-9);
}

void Camera::reorthonormalize() {
  const glm::dvec3 b = glm::normalize(back());
  const glm::dvec3 r = glm::normalize(right() - glm::dot(right(), b) * b);
  orientation_ = glm::dmat3(r, glm::cross(b, r), b);
}

}  // namespace voxlink::render
