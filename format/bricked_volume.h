// SPDX-License-Identifier: BSD-3-Clause
// A whole volume in memory, already bricked, written in one call: what scenes, tests and tools
// that build a small file whole use. The converter streams instead (format/file_writer.h), which
// this file writes through.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "base/error.h"
#include "format/file_writer.h"
#include "format/layout.h"

namespace voxlink::format {

// The version 2 sections of a scene (see format/layout.h): masks over the voxels in file order,
// payloads over the voxels whose bit is set.
struct SceneSections {
  std::vector<MaterialRecord> materials;  // MATL
  std::vector<uint32_t> volumeMask;       // VMSK, ceil(voxels / 32) words
  std::vector<uint32_t> surfaceMask;      // SMSK, ceil(voxels / 32) words
  std::vector<uint32_t> surface;          // SURF, one word per surface voxel
  std::vector<SphereRecord> spheres;      // SPHR (empty: no sphere sections)
  std::vector<uint32_t> sphereMask;       // PMSK, ceil(voxels / 32) words when there are spheres
  std::vector<uint32_t> sphereRefStart;   // SROF, sphere voxels + 1 entries
  std::vector<uint32_t> sphereRefs;       // SRID
  // Version 2.1 (surfaceMode not kMean): per surface voxel, its list in FRAG or TRID.
  SurfaceMode surfaceMode = SurfaceMode::kMean;
  std::vector<uint32_t> fragmentStart;    // FROF, surface voxels + 1 entries
  std::vector<FragmentRecord> fragments;  // FRAG (kPlanes)
  std::vector<uint32_t> triangleRefs;     // TRID (kTriangles)
  std::vector<TriangleRecord> triangles;  // TRIS (kTriangles)
};

// Sets the version 2 fields of a header from the scene sections it will carry.
void makeSceneHeader(FileHeader& header, const SceneSections& scene);

// A whole file held in memory: what small producers (tests, voxelizers) build and write.
struct BrickedVolume {
  VolumeDescription description;
  std::string metaJson = "{}";
  std::vector<uint32_t> occupancy;     // BOCC
  std::vector<uint32_t> rank;          // BRNK
  std::vector<uint32_t> voxelBase;     // BVOX, occupied bricks + 1 entries
  std::vector<uint16_t> rowStarts;     // ROWS
  std::vector<uint32_t> rowMasks;      // MASK
  std::vector<uint8_t> values;         // VALU, voxelCount * storedSize bytes (unpadded); empty in
                                       //   a scene without volume samples (format/voxlink_file.h)
  std::vector<uint16_t> gradients;     // GRAD, as VALU
  std::optional<SceneSections> scene;  // present: a version 2 file

  uint64_t voxelCount() const { return voxelBase.empty() ? 0 : voxelBase.back(); }
  uint64_t occupiedBrickCount() const { return voxelBase.empty() ? 0 : voxelBase.size() - 1; }
};

Status writeBrickedVolume(const std::string& path, const BrickedVolume& volume);

// Fills BRNK from BOCC.
std::vector<uint32_t> rankFromOccupancy(const std::vector<uint32_t>& occupancy);

// The position of voxel (x, y, z) in file order: (brick, row, depth) packed into one number.
// Voxels sorted by this key are in the order of VALU, GRAD and every per-voxel section.
uint64_t fileOrderKey(const VolumeDescription& d, uint32_t x, uint32_t y, uint32_t z);

// Collects voxels in any order and sorts them into bricks and rows.
class BrickedVolumeBuilder {
 public:
  explicit BrickedVolumeBuilder(VolumeDescription description);
  // `storedBits` is the stored value's bit pattern (u8, u16, f16 or f32 per valueType).
  void add(uint32_t x, uint32_t y, uint32_t z, uint32_t storedBits, uint16_t gradient);
  size_t size() const { return voxels_.size(); }
  // Fails on coordinates outside dims or on a voxel added twice.
  Result<BrickedVolume> build(std::string metaJson = "{}") const;

 private:
  struct Entry {
    uint64_t key;  // brick, row, depth
    uint32_t bits;
    uint16_t gradient;
    uint32_t x, y, z;
  };
  VolumeDescription description_;
  std::vector<Entry> voxels_;
};

}  // namespace voxlink::format
