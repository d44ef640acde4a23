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
  if (restBounds.isEmpty()) return Status::ok();
  const geometry::Bounds3 box = gridBox(grid);
  std::array<double, 3> centre{}, half{};
  double radius = 0;
  for (int a = 0; a < 3; ++a) {
    centre[a] = 0.5 * (double(restBounds.min[a]) + restBounds.max[a]);
    half[a] = 0.5 * (double(restBounds.max[a]) - restBounds.min[a]);
    radius += half[a] * half[a];
  }
  if (animation.rotates()) half.fill(std::sqrt(radius));
  static const char* kAxis = "xyz";
  for (size_t k = 0; k < animation.keys.size(); ++k) {
    const AnimationKey& key = animation.keys[k];
    for (int a = 0; a < 3; ++a) {
      const double lo = centre[a] + key.translate[a] - half[a];
      const double hi = centre[a] + key.translate[a] + half[a];
      if (lo < box.min[a] || hi > box.max[a])
        return makeError(ErrorCode::kInvalidArgument, where, ".animation.keys[", k,
                         "]: moves the object outside the grid (", kAxis[a], " ", lo, "..", hi,
                         " not in ", box.min[a], "..", box.max[a],
                         animation.rotates() ? ", rotating: its bounding sphere)" : ")");
    }
  }
  return Status::ok();
}

}  // namespace voxlink::scene
