// SPDX-License-Identifier: BSD-3-Clause
// Meshes through assimp (geometry/mesh_loader.h): OBJ (+ MTL files given as extra fuzz files),
// PLY, OFF and STL. The extension, which picks assimp's importer, follows the content: "ply"
// starts a PLY file, "OFF", "COFF" or "NOFF" an OFF file, "solid" or a NUL byte in the 84-byte
// binary header an STL file, anything else is read as OBJ. A loaded mesh must keep its own
// invariants; a broken one aborts (a finding).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string_view>

#include "fuzz/fuzz_input.h"
#include "fuzz/fuzz_targets.h"
#include "geometry/mesh_loader.h"

namespace voxlink::fuzz {
namespace {

std::string meshFileName(Input input) {
  const std::string_view text(reinterpret_cast<const char*>(input.data()), input.size());
  if (text.starts_with("ply")) return "input.ply";
  if (text.starts_with("OFF") || text.starts_with("COFF") || text.starts_with("NOFF"))
    return "input.off";
  if (text.starts_with("solid")) return "input.stl";
  if (text.substr(0, 84).find('\0') != std::string_view::npos) return "input.stl";
  return "input.obj";
}

[[noreturn]] void broken(const char* what) {
  std::fprintf(stderr, "loaded mesh is inconsistent: %s\n", what);
  std::abort();
}

void checkMesh(const geometry::TriangleMesh& mesh) {
  if (mesh.positions.size() % 3 != 0) broken("positions not in triples");
  if (mesh.triangles.size() % 3 != 0) broken("triangle indices not in triples");
  if (mesh.triangleMaterials.size() != mesh.triangleCount()) broken("material per triangle");
  if (!mesh.normals.empty() && mesh.normals.size() != mesh.positions.size()) broken("normals");
  if (mesh.triangleCount() == 0) broken("no triangles");
  for (uint32_t index : mesh.triangles)
    if (index >= mesh.vertexCount()) broken("vertex index out of range");
  for (uint16_t material : mesh.triangleMaterials)
    if (material >= mesh.materials.size()) broken("material index out of range");
  for (float p : mesh.positions)
    if (!std::isfinite(p)) broken("non-finite position");
  if (geometry::meshBounds(mesh).isEmpty()) broken("empty bounds");
}

}  // namespace

Status fuzzMesh(Input input) {
  const std::string path = scratch().write(splitFuzzFiles(input, meshFileName(input)));
  // A fuzz input is at most 64 KB; a million triangles is far beyond what it can describe.
  auto mesh = geometry::loadMesh(path, {.maxTriangles = 1'000'000});
  if (!mesh) return mesh.status();
  checkMesh(*mesh);
  return Status::ok();
}

}  // namespace voxlink::fuzz
