// SPDX-License-Identifier: BSD-3-Clause
// A dynamic scene (docs/dynamic-scenes.md): a scene file whose meshes, sphere sets and particles
// with an `animation` move. The static objects are voxelized once (scene::buildScene, the exact
// CPU path) into a scene file; every frame, setTime() places the moving objects at their pose and
// re-voxelizes only them on the GPU: meshes into the dynamic layer (render/gl/gl_dynamic_layer.h),
// of which a mesh that has stood for two updates is kept and not re-voxelized again; spheres into
// the sphere lists (render/gl/gl_dynamic_spheres.h), where only the sets that moved are
// re-marked and a set that has stood for two updates is kept.
// renderer() draws all. The grid is the whole scene's at rest, and every moving object must stay
// inside it at every key.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "base/error.h"
#include "format/voxlink_file.h"
#include "geometry/particle_loader.h"
#include "geometry/voxel_grid.h"
#include "render/camera.h"
#include "render/gl/dynamic_scene_renderer.h"
#include "render/gl/gl_dynamic_layer.h"
#include "render/gl/gl_dynamic_spheres.h"
#include "scene/scene_assembly.h"
#include "scene/scene_description.h"

namespace voxlink::viewer {

struct DynamicSceneStats {
  double staticBuildSeconds = 0;  // the static objects, once
  uint64_t movingTriangles = 0;
  uint64_t layerBytes = 0;  // GPU memory of the dynamic layer
  // The last update: triangles re-voxelized, and moving meshes restored from the kept layer
  // (unmoved for two updates in a row) instead.
  uint64_t reVoxelizedTriangles = 0;
  uint32_t keptMeshes = 0;
  uint64_t movingSpheres = 0;  // of all moving sphere sets and particles
  // The last update: spheres and sphere sets re-marked (none when no set moved; a set that stood
  // for two updates in a row is kept in the lists instead, as a mesh in the layer), and sets kept.
  uint64_t reVoxelizedSpheres = 0;
  uint32_t reMarkedSphereSets = 0;
  uint32_t keptSphereSets = 0;
};

class DynamicScene {
  struct Moving {
    size_t object = 0;                  // index in the description
    std::vector<double> restPositions;  // world, 3 per vertex
    std::vector<uint32_t> triangles;
    // A sphere set or particles instead of a mesh: its spheres as the file gives them (no
    // transform, the radius unscaled; the material the scene's), placed per pose as
    // scene::placeSceneGeometry places them, so that a pose's spheres are a frozen scene's.
    bool isSpheres = false;
    std::vector<geometry::Sphere> fileSpheres;
    std::array<double, 3> centre{};  // of the rest bounds: the rotation's pivot
    geometry::Bounds3 restBounds;
    scene::Pose pose;  // the current one
    // In the layer: the pose of the last update, the updates in a row it has not moved for,
    // whether the layer's (a sphere set: the sphere lists') kept part holds it; where its
    // vertices and triangles start in gridPositions_ (floats) and triangles_ (indices), or its
    // spheres in the sphere lists' records.
    std::optional<scene::Pose> uploaded;
    uint32_t unmovedUpdates = 0;
    bool kept = false;
    size_t firstFloat = 0, firstIndex = 0;
    uint32_t firstSphere = 0;
  };

 public:
  // What load() does without GL: the static part built and written, the moving meshes placed
  // and checked against the grid, the layer's sizes. The viewer runs it before it opens a
  // window, so a bad scene is an error before anything shows.
  struct Prepared {
    scene::SceneDescription scene;
    std::string staticFile;
    geometry::VoxelGrid grid;
    std::vector<Moving> moving;
    uint32_t brick = 0;  // the layer's brick edge (dynamic_scene.cpp says why it may differ)
    uint64_t bricks = 0, triangles = 0;
    uint64_t spheres = 0, sphereReferences = 0;  // the bound on (sphere, brick) references
    // At most this many bytes per storage buffer of the layer's pool (tests split a small pool
    // this way; 0: GL_MAX_SHADER_STORAGE_BLOCK_SIZE).
    uint64_t poolBufferBytes = 0;
    geometry::Bounds3 restBounds;
    double seconds = 0;
  };
  // `staticFile`: where the static part is written (a scratch path the caller owns); `progress`
  // follows scene::buildScene's stages. Errors: no moving object, none static, an object that
  // leaves the grid, and what buildScene returns.
  static Result<Prepared> prepare(const scene::SceneDescription& scene,
                                  const std::string& staticFile,
                                  const scene::SceneProgress& progress = {});
  // Needs a current GL 4.5 context. Errors: what render::gl::GlDynamicLayer::create and the
  // renderer return.
  static Result<std::unique_ptr<DynamicScene>> load(Prepared prepared);
  // prepare() and load() in one.
  static Result<std::unique_ptr<DynamicScene>> load(const scene::SceneDescription& scene,
                                                    const std::string& staticFile);

  // Places the moving meshes at `seconds` and re-voxelizes those that moved on the GPU (queued,
  // no read-back; uploadPoses() says which).
  Status setTime(double seconds);
  // The moving objects (meshes, sphere sets, particles), numbered as setPose() numbers them: the
  // object's index in the description and its world bounds at rest (its transform, no pose).
  struct MovingObject {
    size_t object = 0;
    geometry::Bounds3 restBounds;
  };
  std::vector<MovingObject> movingObjects() const;
  // Places moving mesh `index` at `pose` (instead of its animation's; the others keep their
  // current pose) and re-voxelizes those that moved; the static part is kept. For a user who
  // drags an object. Errors: an index out of range, a non-finite pose, a pose that takes the
  // rest bounds' corners outside the grid (callers clamp first: viewer/app/detail/object_drag.h).
  Status setPose(size_t index, const scene::Pose& pose);
  const scene::Pose& pose(size_t index) const { return moving_.at(index).pose; }
  render::gl::DynamicSceneRenderer& renderer() { return *renderer_; }
  // The moving meshes' layer; its bricks are the file's, or 8^3 voxels where those are bigger.
  const render::gl::GlDynamicLayer& layer() const { return layer_; }
  // The moving spheres' lists (per 8^3 voxels, dynamic_scene.cpp says why), or null where no
  // sphere set moves.
  const render::gl::GlDynamicSpheres* spheres() const { return spheres_.get(); }
  // Waits and checks the last update of both: an error where bricks or references were dropped.
  Status checkLastUpdate() const;
  const geometry::VoxelGrid& grid() const { return grid_; }
  const DynamicSceneStats& stats() const { return stats_; }
  // Places every moving mesh at once (`poses` in movingObjects()' order) and re-voxelizes those
  // that moved in one update: a frame where some follow their animation and a dragged one does
  // not. Errors as
  // setPose's; on an error no pose changes.
  Status setPoses(const std::vector<scene::Pose>& poses);
  // Mesh `index`'s world box at `pose`: the box around its rest bounds' corners, posed (in
  // double, as setPose checks them against the grid).
  render::Box posedBox(size_t index, const scene::Pose& pose) const;
  const scene::SceneDescription& description() const { return scene_; }
  // The scene with every moving object frozen at its pose at `seconds` (its transform composed
  // with the pose, no animation) and the same grid: what `scene build` makes of that frame.
  scene::SceneDescription frozenAt(double seconds) const;

 private:
  Status checkPose(size_t index, const scene::Pose& pose) const;
  Status uploadPoses();
  // Re-voxelizes `meshes` (indices into moving_) into the layer, on its kept part or not.
  Status reVoxelize(const std::vector<size_t>& meshes, bool onKept);
  // Re-marks the sphere sets that moved (`still`: per moving object, whether its pose is the
  // last update's), on the lists' kept part of sets that stand, as uploadPoses() does for meshes.
  Status reMarkSpheres(const std::vector<bool>& still);
  // Sphere set `index`'s spheres at its pose, as the frozen scene's static build places them.
  std::vector<render::gl::DynamicSphere> placedSpheres(size_t index) const;
  DynamicScene(scene::SceneDescription scene, format::VoxLinkFile file,
               render::gl::GlDynamicLayer layer);
  scene::SceneDescription scene_;
  format::VoxLinkFile file_;
  render::gl::GlDynamicLayer layer_;
  std::unique_ptr<render::gl::GlDynamicSpheres> spheres_;
  std::unique_ptr<render::gl::DynamicSceneRenderer> renderer_;
  geometry::VoxelGrid grid_;
  std::vector<Moving> moving_;
  std::vector<uint32_t> triangles_, materials_;  // all moving meshes, concatenated
  std::vector<float> gridPositions_;
  geometry::Bounds3 restBounds_;  // the whole scene at rest: the grid's
  DynamicSceneStats stats_;
};

}  // namespace voxlink::viewer
