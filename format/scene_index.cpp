// SPDX-License-Identifier: BSD-3-Clause
#include "format/scene_index.h"

namespace voxlink::format {

SceneIndex::SceneIndex(const VoxLinkFile& file) : file_(file), scene_(file.isScene()) {
  if (!scene_) return;
  volume_ = MaskRank(file.volumeMaskWords());
  surface_ = MaskRank(file.surfaceMaskWords());
  spheres_ = MaskRank(file.sphereMaskWords());
}

int64_t SceneIndex::volumeSlot(uint64_t voxel) const {
  if (!scene_) return static_cast<int64_t>(voxel);
  return volume_.has(voxel) ? int64_t{volume_.slot(voxel)} : int64_t{-1};
}

uint32_t SceneIndex::surfaceWord(uint64_t voxel) const {
  if (!scene_ || !surface_.has(voxel)) return kNoSurface;
  return file_.surfaceWords()[surface_.slot(voxel)];
}

std::pair<uint32_t, uint32_t> SceneIndex::sphereRefs(uint64_t voxel) const {
  if (!scene_ || !spheres_.has(voxel)) return {0, 0};
  const auto starts = file_.sphereRefStarts();
  const uint32_t s = spheres_.slot(voxel);
  return {starts[s], starts[s + 1]};
}

}  // namespace voxlink::format
