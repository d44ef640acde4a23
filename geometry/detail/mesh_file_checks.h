// SPDX-License-Identifier: BSD-3-Clause
// Checks of mesh files that assimp 5.2 does not make, run before it reads them: a PLY header
// without `end_header` (assimp loops forever), PLY or OFF counts the file cannot hold (assimp
// reserves them first and fails with a bare std::bad_alloc), and OFF face indices past the
// vertices (assimp clamps them to the last vertex and logs, so a damaged file loaded as a wrong
// mesh), and MTL statements that assimp writes into a material that does not exist yet (a
// SEGV). Each error names the file and the field.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include "base/error.h"
#include "geometry/detail/ply_header.h"

namespace voxlink::geometry {

// The file's first `bytes` bytes, fewer when it is shorter, empty when it cannot be read.
std::string readFileHead(const std::string& path, size_t bytes);

bool looksLikePly(const std::string& path);  // starts with "ply" and a line end
bool looksLikeOff(const std::string& path);  // starts with [ST][C][N][4][n]OFF

// `header`: readPlyHeader(path), read once by the loader.
Status checkPlyFile(const std::string& path, const PlyHeader& header);
Status checkOffFile(const std::string& path);

// An MTL file that `objPath` loads: a texture map (map_Kd, bump, disp, norm, ...) or an
// anisotropy (`a...`) statement before the first `newmtl` is refused, naming the line; assimp
// 5.2.5 stores them through a null material pointer. Other statements there it ignores, and so
// does this check. mtl_file_check.cpp says how the statements are found.
Status checkMtlFile(const std::string& path, const std::string& objPath);

// The faces an OFF header declares; 0 when it says none or is no OFF file (a PLY's are its
// header's `face` element). loadMesh compares it with the triangles it got: far fewer means
// faces were lost.
uint64_t declaredOffFaceCount(const std::string& path);

}  // namespace voxlink::geometry
