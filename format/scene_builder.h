// SPDX-License-Identifier: BSD-3-Clause
// Collects what a scene puts into each voxel — a volume sample, a surface fragment, references
// to implicit spheres — in any order, merges the contributions per voxel and sorts them into the
// bricks and rows of a version 2 file (format/layout.h). A builder given volume samples only
// yields the version 1 sections a converter would write for the same voxels.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "base/error.h"
#include "format/bricked_volume.h"
#include "format/layout.h"

namespace voxlink::format {

class SceneBuilder {
 public:
  explicit SceneBuilder(VolumeDescription description);

  // The tables the per-voxel entries index into.
  void setMaterials(std::vector<MaterialRecord> materials) { materials_ = std::move(materials); }
  void setSpheres(std::vector<SphereRecord> spheres) { spheres_ = std::move(spheres); }

  // `storedBits` as for BrickedVolumeBuilder::add (valueType of the description).
  void addVolumeSample(uint32_t x, uint32_t y, uint32_t z, uint32_t storedBits, uint16_t gradient);
  void addSurface(uint32_t x, uint32_t y, uint32_t z, uint16_t normalCode, uint16_t material);
  void addSphereRef(uint32_t x, uint32_t y, uint32_t z, uint32_t sphere);
  void reserve(size_t entries) { entries_.reserve(entries); }

  // Fails on coordinates outside dims, two volume samples or two surface fragments in one voxel,
  // a material or sphere index beyond its table, or a table that the format cannot hold. The
  // result has scene sections unless only volume samples were added.
  Result<BrickedVolume> build(std::string metaJson = "{}") const;

 private:
  enum Kind : uint8_t { kVolume = 0, kSurfaceFragment = 1, kSphere = 2 };
  struct Entry {
    uint32_t x, y, z;
    Kind kind;
    uint16_t gradient;  // kVolume
    uint32_t payload;   // stored bits, surface word or sphere index
  };
  VolumeDescription description_;
  std::vector<MaterialRecord> materials_;
  std::vector<SphereRecord> spheres_;
  std::vector<Entry> entries_;
};

}  // namespace voxlink::format
