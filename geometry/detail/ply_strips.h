// SPDX-License-Identifier: BSD-3-Clause
// PLY files whose faces are triangle strips (`element tristrips` with a `vertex_indices` list,
// common in older scanned models). assimp 5.2 writes every triangle of such a file into one face
// slot, so a 268,686-triangle head loaded as one triangle; these files are read here instead.
// A strip (i0 i1 i2 i3 ...) makes the triangles (i0 i1 i2), (i2 i1 i3), (i2 i3 i4), ... with the
// winding alternating, and -1 restarts it; triangles with a repeated vertex (the joins between
// strips) are left out. A `face` element in the same file is triangulated as fans. loadMesh
// sends a PLY here when its header has an element named `tristrips`.
#pragma once

#include <cstdint>
#include <string>

#include "base/error.h"
#include "geometry/detail/ply_header.h"
#include "geometry/triangle_mesh.h"

namespace voxlink::geometry {

// The mesh of a PLY with triangle strips, ASCII or binary of either byte order; one default
// material. Errors name the file, the element and the item (an index outside the vertices, data
// that ends early, a vertex without x, y, z); kTooLarge beyond `maxTriangles`.
Result<TriangleMesh> loadPlyWithStrips(const std::string& path, const PlyHeader& header,
                                       uint64_t maxTriangles);

}  // namespace voxlink::geometry
