// SPDX-License-Identifier: BSD-3-Clause
// The scene file (docs/scene.md): which meshes, spheres and volume go into one VoxLink buffer,
// their transforms and materials, the grid they are voxelized into, lights and a camera. This
// file only reads and checks the JSON; scene_assembly.h loads and voxelizes what it names.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "base/error.h"
#include "format/layout.h"
#include "geometry/bounds.h"
#include "geometry/fragment_planes.h"
#include "geometry/material.h"
#include "scene/scene_animation.h"

namespace voxlink::scene {

// Row-major 4x4 affine transform (last row 0 0 0 1), object -> world.
struct Transform {
  std::array<double, 16> m{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
  std::array<double, 3> apply(const std::array<double, 3>& p) const;
  // The factor a uniform transform scales lengths by; 0 when the scale is not uniform (spheres
  // need a uniform one).
  double uniformScale() const;
};

struct SceneMaterial {
  geometry::Material material;
  float specular = 0.0f;   // Phong highlight strength, 0..1
  float shininess = 0.0f;  // Phong exponent
};

enum class ObjectKind { kMesh, kParticles, kSphere, kVolume };

struct SceneObject {
  ObjectKind kind = ObjectKind::kMesh;
  std::string path;  // resolved against the scene file's folder; empty for kSphere
  Transform transform;
  std::optional<std::string> material;    // a scene material overriding the file's own
  std::array<double, 3> center{0, 0, 0};  // kSphere
  double radius = 0;                      // kSphere
  double radiusScale = 1;                 // kParticles: multiplies every radius
  // kVolume from a dense source (any file `voxlink convert` reads) rather than a .vxl: what to
  // keep, as convert's options. thresholds: "LO" or "LO,HI" each, a union (--threshold);
  // tfPath: a transfer function JSON (--tf). Both empty: `path` is a .vxl.
  std::vector<std::string> thresholds;
  std::string tfPath;
  // kMesh: keyframed motion (scene_animation.h); `scene build` ignores it (the rest pose).
  std::optional<Animation> animation;
  // The scene file and the object's place in it ("cornell.scene.json: objects[2]"): errors from
  // the object's own files and voxelization start with it.
  std::string where;
};

struct SceneGrid {
  uint32_t resolution = 256;  // voxels along the longest axis of the scene's bounds
  uint32_t brickSize = 8;
  format::Axis axis = format::Axis::kZ;
  // What a surface voxel keeps (`scene build --surface`, format/surface_mode.h) and, for planes,
  // the largest angle between triangle normals that share a fragment (`--fragment-angle`).
  format::SurfaceMode surface = format::SurfaceMode::kMean;
  double fragmentAngleDegrees = geometry::kDefaultMergeAngleDegrees;
  // Set by callers, not the file: fit the grid around these bounds instead of the objects' (a
  // dynamic scene's static part keeps the grid of the whole scene at rest).
  std::optional<geometry::Bounds3> fitBounds;
};

struct Light {
  std::array<double, 3> position{0, 0, 0};
  std::array<double, 3> color{1, 1, 1};
  double intensity = 1;
};

struct SceneDescription {
  std::string path;  // the scene file, for messages
  SceneGrid grid;
  std::vector<std::pair<std::string, SceneMaterial>> materials;  // in file order
  std::vector<SceneObject> objects;
  std::vector<Light> lights;
  std::string cameraJson;  // the "camera" object as written, or empty
  const SceneMaterial* findMaterial(const std::string& name) const;
  // The time one loop of the scene's motion takes: the longest animation `period`, else the
  // latest key (1 s when nothing moves or every key is at 0); the viewer's clock and
  // `bench-render --animate` run over it.
  double animationSpan() const;
};

// Reads and checks a scene file; every error is one line naming the file and the JSON path of
// the bad field ("cornell.scene.json: objects[2].radius: -1 is not > 0").
Result<SceneDescription> readSceneDescription(const std::string& path);
Result<SceneDescription> parseSceneDescription(const std::string& json, const std::string& path);

}  // namespace voxlink::scene
