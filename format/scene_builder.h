// SPDX-License-Identifier: BSD-3-Clause
// Collects what a scene puts into each voxel — a volume sample, a surface fragment, references
// to implicit spheres — in any order, merges the contributions per voxel and sorts them into the
// bricks and rows of a version 2 file (format/layout.h). A builder given volume samples only
// yields the version 1 sections a converter would write for the same voxels.
#pragma once

#include <cstdint>
#include <span>
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
  // Version 2.1: every surface voxel also gets a fragment list (addFragments for kPlanes,
  // addTriangleRefs into `triangles` for kTriangles).
  void setSurfaceMode(SurfaceMode mode) { surfaceMode_ = mode; }
  void setTriangles(std::vector<TriangleRecord> triangles) { triangles_ = std::move(triangles); }

  // `storedBits` as for BrickedVolumeBuilder::add (valueType of the description).
  void addVolumeSample(uint32_t x, uint32_t y, uint32_t z, uint32_t storedBits, uint16_t gradient);
  void addSurface(uint32_t x, uint32_t y, uint32_t z, uint16_t normalCode, uint16_t material);
  void addSphereRef(uint32_t x, uint32_t y, uint32_t z, uint32_t sphere);
  void addFragments(uint32_t x, uint32_t y, uint32_t z, std::span<const FragmentRecord> list);
  void addTriangleRefs(uint32_t x, uint32_t y, uint32_t z, std::span<const uint32_t> list);
  void reserve(size_t entries) { entries_.reserve(entries); }

  // Fails on coordinates outside dims, two volume samples or two surface fragments in one voxel,
  // a material, sphere or triangle index beyond its table, or a table that the format cannot
  // hold; with fragment lists also on a surface voxel without exactly one list, a list without
  // a surface fragment, and a list longer than kMaxFragmentsPerVoxel. The
  // result has scene sections unless only volume samples were added.
  Result<BrickedVolume> build(std::string metaJson = "{}") const;

 private:
  enum Kind : uint8_t { kVolume = 0, kSurfaceFragment = 1, kSphere = 2, kFragmentList = 3 };
  struct Entry {
    uint32_t x, y, z;
    Kind kind;
    uint16_t gradient;  // kVolume; kFragmentList: the list's length (capped at 0xFFFF)
    uint32_t payload;   // stored bits, surface word, sphere index or the list's first entry
  };
  // Appends the voxel's list (planes_ or triangleRefs_ from `first`, `count` long).
  Status appendList(const Entry& e, uint32_t count, SceneSections& scene) const;
  VolumeDescription description_;
  std::vector<MaterialRecord> materials_;
  std::vector<SphereRecord> spheres_;
  std::vector<Entry> entries_;
  SurfaceMode surfaceMode_ = SurfaceMode::kMean;
  std::vector<TriangleRecord> triangles_;
  std::vector<FragmentRecord> planes_;  // every addFragments list, back to back
  std::vector<uint32_t> triangleRefs_;  // every addTriangleRefs list, back to back
};

}  // namespace voxlink::format
