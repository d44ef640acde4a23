// SPDX-License-Identifier: BSD-3-Clause
// Making a static mesh, sphere set or particles of a scene move (docs/dynamic-scenes.md,
// "Dragging a static mesh"): the scene with that object given an animation of one key at rest,
// so DynamicScene::prepare builds the static part without it and voxelizes it on the GPU; the
// rebuild runs on a thread (it needs no GL) while the viewer goes on drawing. Free of GL and GLFW.
#pragma once

#include <atomic>
#include <future>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "base/error.h"
#include "geometry/bounds.h"
#include "scene/scene_description.h"
#include "viewer/dynamic_scene.h"

namespace voxlink::viewer {

// A static mesh, sphere set or particles that can move: its index in the description and its
// world bounds at rest.
struct StaticObject {
  size_t object = 0;
  geometry::Bounds3 restBounds;
};

// The static meshes, sphere sets and particles with a scene material (what a moving object
// needs), placed to get their bounds; none where one static object is left (the static part must
// not become empty).
Result<std::vector<StaticObject>> movableStaticObjects(const scene::SceneDescription& scene);

// `scene` with objects[object] moving (an animation of one key, at rest). Errors, one line naming
// the object: an index out of range, a volume (it does not move), an object without a scene
// material, one that moves already, the last static object (the static part would be empty).
Result<scene::SceneDescription> withObjectMoving(const scene::SceneDescription& scene,
                                                 size_t object);

// DynamicScene::prepare on a thread, with its progress (0..1 over buildScene's stages).
class BackgroundPrepare {
 public:
  BackgroundPrepare(scene::SceneDescription scene, std::string staticFile, size_t object);
  ~BackgroundPrepare();  // waits for the thread
  size_t object() const { return object_; }
  double progress() const { return progress_->load(); }
  // The result once the thread is done (then once only), else none; `wait` blocks until done.
  std::optional<Result<DynamicScene::Prepared>> take(bool wait);
  const std::string& staticFile() const { return staticFile_; }

 private:
  std::string staticFile_;
  size_t object_;
  std::shared_ptr<std::atomic<double>> progress_;
  std::future<Result<DynamicScene::Prepared>> result_;
};

}  // namespace voxlink::viewer
