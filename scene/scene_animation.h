// SPDX-License-Identifier: BSD-3-Clause
// Keyframed motion of a scene object (the scene file's `animation`, docs/dynamic-scenes.md):
// per key a time, a translation and a rotation about the object's centre, linearly interpolated;
// with a period the motion loops, going back from the last key to the first. The static scene
// fixes the grid; a moving object must stay inside it at every key (checkAnimationInGrid).
#pragma once

#include <array>
#include <string>
#include <vector>

#include "base/error.h"
#include "geometry/bounds.h"
#include "geometry/voxel_grid.h"

namespace voxlink::scene {

struct AnimationKey {
  double time = 0;                        // seconds, >= 0, strictly increasing over the keys
  std::array<double, 3> translate{};      // world units, added after the object's transform
  std::array<double, 3> rotateDegrees{};  // about x, y, z (in that order) around the centre
};

struct Animation {
  std::vector<AnimationKey> keys;  // at least one
  double period = 0;               // > last key's time: loops; 0: holds the last key after it
  bool rotates() const;
};

// Where the object is at `seconds` (any finite value; before the first key: the first key).
struct Pose {
  std::array<double, 3> translate{};
  std::array<double, 3> rotateDegrees{};
};
Pose samplePose(const Animation& animation, double seconds);

// World point of a point `p` of the object at rest under `pose`: rotated about `centre`, then
// translated.
std::array<double, 3> applyPose(const Pose& pose, const std::array<double, 3>& centre,
                                const std::array<double, 3>& p);

// The world box the grid's voxels cover (their outer faces).
geometry::Bounds3 gridBox(const geometry::VoxelGrid& grid);

// Errors (one line, `where` = "s.scene.json: objects[1]"): a key, or for a rotating object a
// pose between two keys, that takes the object's rest bounds (rotated with it: their corners)
// outside `grid`. Rotating poses are checked at most a degree apart, each grown by the most a
// point can move between two; a translation between two keys inside the grid stays inside.
Status checkAnimationInGrid(const Animation& animation, const geometry::Bounds3& restBounds,
                            const geometry::VoxelGrid& grid, const std::string& where);

}  // namespace voxlink::scene
