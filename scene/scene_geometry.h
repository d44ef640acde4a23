// SPDX-License-Identifier: BSD-3-Clause
// A scene's geometry placed in world space: every mesh and sphere its file names, loaded, moved by
// its transform and given its index in the scene's one material table. `voxlink scene build`
// voxelizes this; the exact tracer (exact/) ray traces it, so both see the same triangles,
// spheres and materials.
#pragma once

#include <string>
#include <vector>

#include "base/error.h"
#include "format/layout.h"
#include "geometry/bounds.h"
#include "geometry/sphere_voxelizer.h"
#include "geometry/triangle_mesh.h"
#include "scene/scene_description.h"

namespace voxlink::scene {

struct PlacedScene {
  // World coordinates; triangleMaterials and Sphere::material index `materials`. mesh.materials
  // is left empty (the table below is the scene's).
  geometry::TriangleMesh mesh;
  std::vector<geometry::Sphere> spheres;
  geometry::Bounds3 bounds;  // of the triangles and spheres
  // The material table: scene materials by name first, then what files bring; never empty.
  std::vector<std::string> materialNames;
  std::vector<format::MaterialRecord> materials;
  // Volume objects, in file order; not loaded here.
  std::vector<const SceneObject*> volumes;
};

// Loads and places every mesh, particle file and sphere of `scene` (which must outlive the
// result). Errors: a file that does not load, more than format::kMaxMaterials materials.
Result<PlacedScene> placeSceneGeometry(const SceneDescription& scene);

}  // namespace voxlink::scene
