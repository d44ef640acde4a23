// SPDX-License-Identifier: BSD-3-Clause
// An indexed triangle mesh with one material per triangle: what loadMesh returns and what the
// surface voxelizer reads.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "geometry/bounds.h"
#include "geometry/material.h"

namespace voxlink::geometry {

struct TriangleMesh {
  std::vector<float> positions;             // x, y, z per vertex
  std::vector<uint32_t> triangles;          // three vertex indices per triangle
  std::vector<uint16_t> triangleMaterials;  // per triangle: index into `materials`
  std::vector<Material> materials;
  std::vector<float> normals;  // x, y, z per vertex when every part of the file had normals,
                               // else empty (the voxelizer uses face normals either way)

  size_t vertexCount() const { return positions.size() / 3; }
  size_t triangleCount() const { return triangles.size() / 3; }
};

// Bounds of the vertices that triangles use (unused vertices do not count).
Bounds3 meshBounds(const TriangleMesh& mesh);

}  // namespace voxlink::geometry
