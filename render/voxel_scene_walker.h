// SPDX-License-Identifier: BSD-3-Clause
// SceneWalker over a VoxLink file: each voxel cell the ray crosses is looked up
// (format::VoxelLocator) and gives, in this order, its surface fragment (at the chord's entry,
// with the stored polar normal), the nearest exact hit of its spheres inside the chord, and its
// volume sample over the chord: what the GL ray tracer walks, in double precision. Works for
// version 1 files too (every voxel a volume sample).
#pragma once

#include <array>

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
  double shadowStartOffset() const override { return unit_; }
  double opacityUnit() const override { return unit_; }

 private:
  const format::VoxLinkFile& file_;
  format::VoxelLocator locator_;
  format::SceneIndex index_;
  std::array<uint32_t, 3> dims_;
  glm::dvec3 origin_, spacing_;
  double unit_;
  Box box_;
};

}  // namespace voxlink::render
