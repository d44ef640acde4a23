// SPDX-License-Identifier: BSD-3-Clause
// A dense volume in memory, values in float64 source units: what the reference renderer and the
// dense 3D-texture ray caster render, and what tests voxelize into VoxLink files.
#pragma once

#include <array>
#include <cstdint>
#include <glm/glm.hpp>
#include <string>
#include <vector>

#include "base/error.h"
#include "render/camera.h"
#include "sources/volume_source.h"

namespace voxlink::render {

struct DenseVolume {
  std::array<uint32_t, 3> dims{0, 0, 0};
  std::array<double, 3> spacing{1, 1, 1};
  std::array<double, 3> origin{0, 0, 0};  // world position of voxel (0,0,0)'s centre
  ScalarType sourceType = ScalarType::kF64;
  std::vector<double> values;  // x fastest, then y, then z

  uint64_t voxelCount() const { return uint64_t{dims[0]} * dims[1] * dims[2]; }
  uint64_t index(uint32_t x, uint32_t y, uint32_t z) const {
    return (uint64_t{z} * dims[1] + y) * dims[0] + x;
  }
  double at(uint32_t x, uint32_t y, uint32_t z) const { return values[index(x, y, z)]; }
  // Gradient of the values in world units, as the converter computes it: central differences
  // divided by 2 * spacing, one-sided differences (divided by spacing) at the border, 0 along an
  // axis with a single voxel.
  glm::dvec3 gradient(uint32_t x, uint32_t y, uint32_t z) const;
  // The box the voxel cells fill: origin - spacing/2 .. origin + (dims - 1/2) spacing.
  Box worldBox() const;
  double minSpacing() const;
};

// Reads a whole source volume (any reader openVolume() knows).
Result<DenseVolume> loadDenseVolume(sources::VolumeSource& source);
Result<DenseVolume> loadDenseVolume(const std::string& path, const sources::OpenOptions& options);

}  // namespace voxlink::render
