// SPDX-License-Identifier: BSD-3-Clause
#include "scene/scene_animation.h"

#include <algorithm>
#include <cmath>

namespace voxlink::scene {
namespace {

constexpr double kPi = 3.14159265358979323846;

Pose mix(const AnimationKey& a, const AnimationKey& b, double f) {
  Pose p;
  for (int i = 0; i < 3; ++i) {
    p.translate[i] = a.translate[i] + f * (b.translate[i] - a.translate[i]);
    p.rotateDegrees[i] = a.rotateDegrees[i] + f * (b.rotateDegrees[i] - a.rotateDegrees[i]);
  }
  return p;
}

Pose poseOf(const AnimationKey& k) { return {k.translate, k.rotateDegrees}; }

}  // namespace

bool Animation::rotates() const {
  for (const AnimationKey& k : keys)
    for (double r : k.rotateDegrees)
      if (r != 0) return true;
  return false;
}

Pose samplePose(const Animation& animation, double seconds) {
  const auto& keys = animation.keys;
  if (keys.empty()) return {};
  double t = seconds;
  if (animation.period > 0) {
    t = std::fmod(t, animation.period);
    if (t < 0) t += animation.period;
  }
  if (std::isnan(t)) return poseOf(keys.front());  // no comparison below would hold
  if (t <= keys.front().time) {
    // Before the first key of a loop: on the way back from the last key (its time less one
    // period) to the first.
    if (animation.period > 0 && keys.size() > 1) {
      const double from = keys.back().time - animation.period;
      return mix(keys.back(), keys.front(), (t - from) / (keys.front().time - from));
    }
    return poseOf(keys.front());
  }
  if (t >= keys.back().time) {
    if (animation.period > 0 && keys.size() > 1) {
      const double to = keys.front().time + animation.period;
      return mix(keys.back(), keys.front(), (t - keys.back().time) / (to - keys.back().time));
    }
    return poseOf(keys.back());
  }
  const auto next = std::upper_bound(keys.begin(), keys.end(), t,
                                     [](double v, const AnimationKey& k) { return v < k.time; });
  const AnimationKey& b = *next;
  const AnimationKey& a = *(next - 1);
  return mix(a, b, (t - a.time) / (b.time - a.time));
}

std::array<double, 3> applyPose(const Pose& pose, const std::array<double, 3>& centre,
                                const std::array<double, 3>& p) {
  std::array<double, 3> q{p[0] - centre[0], p[1] - centre[1], p[2] - centre[2]};
  for (int axis = 0; axis < 3; ++axis) {  // about x, then y, then z, as the scene's "rotate"
    const double radians = pose.rotateDegrees[axis] * kPi / 180;
    if (radians == 0) continue;
    const double c = std::cos(radians), s = std::sin(radians);
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    const double qu = q[u], qv = q[v];
    q[u] = c * qu - s * qv;
    q[v] = s * qu + c * qv;
  }
  for (int a = 0; a < 3; ++a) q[a] += centre[a] + pose.translate[a];
  return q;
}

geometry::Bounds3 gridBox(const geometry::VoxelGrid& grid) {
  geometry::Bounds3 box;
  for (int a = 0; a < 3; ++a) {
    box.min[a] = float(grid.origin[a] - 0.5 * grid.spacing);
    box.max[a] = float(grid.origin[a] + (double(grid.dims[a]) - 0.5) * grid.spacing);
  }
  return box;
}

Status checkAnimationInGrid(const Animation& animation, const geometry::Bounds3& restBounds,
                            const geometry::VoxelGrid& grid, const std::string& where) {
  if (restBounds.isEmpty() || animation.keys.empty()) return Status::ok();
  const geometry::Bounds3 box = gridBox(grid);
  std::array<double, 3> centre{};
  double radius = 0;
  for (int a = 0; a < 3; ++a) {
    centre[a] = 0.5 * (double(restBounds.min[a]) + restBounds.max[a]);
    const double half = 0.5 * (double(restBounds.max[a]) - restBounds.min[a]);
    radius += half * half;
  }
  radius = std::sqrt(radius);
  static const char* kAxis = "xyz";
  // The box of the rest bounds' corners under `pose`, grown by `margin`, inside the grid?
  auto check = [&](const Pose& pose, double margin, const std::string& at) -> Status {
    std::array<double, 3> lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
    for (int c = 0; c < 8; ++c) {
      const std::array<double, 3> corner{(c & 1) ? restBounds.max[0] : restBounds.min[0],
                                         (c & 2) ? restBounds.max[1] : restBounds.min[1],
                                         (c & 4) ? restBounds.max[2] : restBounds.min[2]};
      const auto p = applyPose(pose, centre, corner);
      for (int a = 0; a < 3; ++a) {
        lo[a] = std::min(lo[a], p[a] - margin);
        hi[a] = std::max(hi[a], p[a] + margin);
      }
    }
    for (int a = 0; a < 3; ++a)
      if (lo[a] < box.min[a] || hi[a] > box.max[a])
        return makeError(ErrorCode::kInvalidArgument, where, ".animation.", at,
                         ": moves the object outside the grid (", kAxis[a], " ", lo[a], "..", hi[a],
                         " not in ", box.min[a], "..", box.max[a], ")");
    return Status::ok();
  };
  const auto& keys = animation.keys;
  for (size_t k = 0; k < keys.size(); ++k)
    VOXLINK_RETURN_IF_ERROR(check(poseOf(keys[k]), 0, cat("keys[", k, "]")));
  if (!animation.rotates()) return Status::ok();  // translations between keys inside stay inside
  // Rotating: poses along each segment (the loop's way back included) at most a degree apart;
  // between two, a point moves at most radius x the angle turned, the margin.
  const size_t segments = keys.size() - 1 + (animation.period > 0 && keys.size() > 1 ? 1 : 0);
  for (size_t k = 0; k < segments; ++k) {
    const AnimationKey& a = keys[k];
    const AnimationKey& b = keys[(k + 1) % keys.size()];
    double turn = 0;
    for (int i = 0; i < 3; ++i) turn += std::abs(b.rotateDegrees[i] - a.rotateDegrees[i]);
    const int steps = std::max(1, int(std::ceil(turn)));
    const double margin = radius * (turn / steps) * kPi / 180;
    for (int i = 1; i < steps; ++i)
      VOXLINK_RETURN_IF_ERROR(check(mix(a, b, double(i) / steps), margin,
                                    cat("keys[", k, "]..keys[", (k + 1) % keys.size(), "]")));
    if (steps == 1 && turn > 0)
      VOXLINK_RETURN_IF_ERROR(
          check(mix(a, b, 0.5), margin, cat("keys[", k, "]..keys[", (k + 1) % keys.size(), "]")));
  }
  return Status::ok();
}

}  // namespace voxlink::scene
