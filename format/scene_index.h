// SPDX-License-Identifier: BSD-3-Clause
// Per-voxel access to what a file stores in each voxel, for version 1 (every voxel a volume
// sample) and version 2 (masks and slots, format/layout.h) alike. Built once per opened file.
#pragma once

#include <cstdint>
#include <utility>

#include "format/layout.h"
#include "format/mask_rank.h"
#include "format/voxlink_file.h"

namespace voxlink::format {

class SceneIndex {
 public:
  explicit SceneIndex(const VoxLinkFile& file);

  // Slot of voxel i in VALU/GRAD, or -1 when it has no volume sample.
  int64_t volumeSlot(uint64_t voxel) const;
  // Its surface fragment word, or kNoSurface.
  uint32_t surfaceWord(uint64_t voxel) const;
  // Its range of SRID entries (empty when it references no sphere).
  std::pair<uint32_t, uint32_t> sphereRefs(uint64_t voxel) const;

  const MaskRank& volume() const { return volume_; }
  const MaskRank& surface() const { return surface_; }
  const MaskRank& spheres() const { return spheres_; }

 private:
  const VoxLinkFile& file_;
  bool scene_;
  MaskRank volume_, surface_, spheres_;
};

}  // namespace voxlink::format
