// SPDX-License-Identifier: BSD-3-Clause
// Loads a triangle mesh with its materials from OBJ (+ MTL), PLY (ASCII, binary of either byte
// order), STL, glTF and the other formats assimp reads.
//
//   auto mesh = voxlink::geometry::loadMesh("bunny.obj");
//   if (!mesh) report(mesh.message());
//
// Polygons are triangulated; points and lines are dropped; degenerate triangles are kept (the
// voxelizer handles them). Node transforms (glTF, FBX, ...) are applied to the positions.
// Vertices that share a position are not merged: OBJ gives one vertex per face corner.
// Errors (one line naming the file): missing or unreadable file, a file assimp cannot parse, no
// triangles, a non-finite vertex (for OBJ with its line number), more than maxTriangles
// triangles, more than 65536 materials, an MTL texture map or anisotropy statement before the
// first `newmtl` (assimp 5.2.5 crashes on those; the error names the MTL file and line).
//
// An OBJ whose `mtllib` file is missing gets the MTL named like the OBJ itself
// (scene.obj -> scene.mtl) when that exists: data sets renamed on download keep their materials.
#pragma once

#include <cstdint>
#include <string>

#include "base/error.h"
#include "geometry/triangle_mesh.h"

namespace voxlink::geometry {

inline constexpr uint64_t kDefaultMaxTriangles = 200'000'000;

struct MeshLoadOptions {
  uint64_t maxTriangles = kDefaultMaxTriangles;  // more is an error (kTooLarge)
};

Result<TriangleMesh> loadMesh(const std::string& path, const MeshLoadOptions& options = {});

}  // namespace voxlink::geometry
