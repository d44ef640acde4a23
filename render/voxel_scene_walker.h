// SPDX-License-Identifier: BSD-3-Clause
// SceneWalker over a VoxLink file: each voxel cell the ray crosses is looked up
// (format::VoxelLocator) and gives its surface hit, the nearest exact hit of its spheres inside
// the chord (the two in order of distance), and its volume sample over the chord: what the GL
// ray tracer walks, in double precision. The surface hit of a version 2.0 file (one fragment)
// is at the chord's entry with the stored polar normal; with fragment lists (version 2.1) it is
// the nearest intersection inside the chord of the voxel's planes or referenced triangles, with
// that fragment's normal and material, and a voxel crossed without one is passed; a plane hit
// counts only inside its fragment's extent (version 2.2, format/fragment_extent.h). Works for
// version 1 files too (every voxel a volume sample).
#pragma once

#include <array>
#include <vector>

#include "format/fragment_extent.h"
#include "format/scene_index.h"
#include "format/voxel_locator.h"
#include "format/voxlink_file.h"
#include "render/scene_walker.h"

namespace voxlink::render {

class VoxelSceneWalker : public SceneWalker {
 public:
  // The file must outlive the walker.
  explicit VoxelSceneWalker(const format::VoxLinkFile& file);

  void walk(const Ray& ray, double tMin, double tMax,
            const std::function<bool(const SceneEvent&)>& visit) const override;
  std::span<const format::MaterialRecord> materials() const override;
  Box bounds() const override { return box_; }
  double surfaceOffset() const override;
  double shadowStartOffset() const override;
  double opacityUnit() const override { return unit_; }

 private:
  const format::VoxLinkFile& file_;
  format::VoxelLocator locator_;
  format::SceneIndex index_;
  std::array<uint32_t, 3> dims_;
  glm::dvec3 origin_, spacing_;
  double unit_;
  Box box_;
  format::SurfaceMode mode_;
  std::vector<glm::dvec3> planeNormals_;              // FRAG's normals, decoded once
  std::vector<format::FragmentExtent> planeExtents_;  // FRAG's extents (2.2), decoded once

  // The nearest hit in [ta, tb) of surface voxel `slot`'s fragment list (planes: the chord grown
  // by kPlaneHitTolerance, not before t = 0), or t = HUGE_VAL.
  SceneEvent listHit(const Ray& ray, const glm::ivec3& cell, uint32_t slot, double ta,
                     double tb) const;
};

}  // namespace voxlink::render
