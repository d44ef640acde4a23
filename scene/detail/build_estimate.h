// SPDX-License-Identifier: BSD-3-Clause
// How many voxels a scene build will store, and how much memory building them takes, estimated
// before any voxelizing: a resolution the machine cannot hold is refused at once with the field
// to change, instead of after minutes of work by std::bad_alloc or the kernel's OOM killer.
#pragma once

#include <cstdint>
#include <string>

#include "base/error.h"
#include "base/process_memory.h"
#include "format/file_writer.h"
#include "scene/scene_geometry.h"

namespace voxlink::scene {

struct SceneBuildEstimate {
  // Lower estimates: a triangle overlaps at least the voxels its three axis projections cover
  // (the sum of its projected areas in voxel units), a sphere's shell at least 1.5 x its area.
  double surfaceVoxels = 0;
  double sphereRefs = 0;
  double volumeVoxels = 0;  // exact: the volume's stored voxels
  double peakBytes = 0;     // the voxels times what building one takes at the peak
};

// Peak bytes per voxel entry while building: peak RSS over entries, measured with /usr/bin/time on
// the sample scenes at 2048 voxels and a scene of the 1024^3 foot (docs/scene.md, "Memory");
// rounded down, so that the check refuses only builds that cannot fit.
inline constexpr double kSurfaceVoxelBuildBytes = 104;  // measured 112-114
inline constexpr double kSphereRefBuildBytes = 96;      // measured 105-106
inline constexpr double kVolumeVoxelBuildBytes = 96;    // measured 106

SceneBuildEstimate estimateSceneBuild(const PlacedScene& placed,
                                      const format::VolumeDescription& grid, uint64_t volumeVoxels);

// kTooLarge, naming the scene file and the resolution, when the estimate exceeds `memoryBytes`.
Status checkSceneBuildFits(const SceneBuildEstimate& estimate, uint64_t memoryBytes,
                           const std::string& scenePath, uint32_t resolution, bool hasVolume);

}  // namespace voxlink::scene
