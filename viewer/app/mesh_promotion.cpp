// SPDX-License-Identifier: BSD-3-Clause
#include "viewer/app/detail/mesh_promotion.h"

#include <chrono>
#include <cstring>

#include "scene/scene_geometry.h"

namespace voxlink::viewer {
namespace {

std::string objectWhere(const scene::SceneDescription& scene, size_t object) {
  return cat(scene.path, ": objects[", object, "]");
}

}  // namespace

Result<std::vector<StaticObject>> movableStaticObjects(const scene::SceneDescription& scene) {
  std::vector<StaticObject> objects;
  size_t still = 0;
  for (const scene::SceneObject& o : scene.objects) still += o.animation ? 0 : 1;
  if (still <= 1) return objects;  // the last static object stays
  for (size_t i = 0; i < scene.objects.size(); ++i) {
    const scene::SceneObject& o = scene.objects[i];
    if (o.kind == scene::ObjectKind::kVolume || o.animation || !o.material) continue;
    scene::SceneDescription one = scene;
    one.objects = {o};
    VOXLINK_ASSIGN_OR_RETURN(scene::PlacedScene placed, scene::placeSceneGeometry(one));
    objects.push_back({i, placed.bounds});
  }
  return objects;
}

Result<scene::SceneDescription> withObjectMoving(const scene::SceneDescription& scene,
                                                 size_t object) {
  if (object >= scene.objects.size())
    return makeError(ErrorCode::kInvalidArgument, scene.path, ": objects[", object,
                     "] does not exist (", scene.objects.size(), " objects)");
  const scene::SceneObject& o = scene.objects[object];
  const std::string where = objectWhere(scene, object);
  if (o.kind == scene::ObjectKind::kVolume)
    return makeError(ErrorCode::kUnsupported, where,
                     ": only meshes, sphere sets and particles move (a volume stays in the static "
                     "part)");
  if (o.animation) return makeError(ErrorCode::kInvalidArgument, where, ": moves already");
  if (!o.material)
    return makeError(ErrorCode::kUnsupported, where,
                     o.kind == scene::ObjectKind::kMesh
                         ? ": a moving mesh needs a \"material\" from \"materials\" (its file's "
                           "own materials are not kept per triangle in the GPU layer)"
                         : ": moving spheres need a \"material\" from \"materials\" (the static "
                           "part's material table holds the scene's)");
  size_t still = 0;
  for (const scene::SceneObject& other : scene.objects) still += other.animation ? 0 : 1;
  if (still <= 1)
    return makeError(ErrorCode::kUnsupported, where,
                     ": the last static object cannot move (the static part would be empty)");
  scene::SceneDescription moved = scene;
  moved.objects[object].animation = scene::Animation{{scene::AnimationKey{}}, 0};
  return moved;
}

BackgroundPrepare::BackgroundPrepare(scene::SceneDescription scene, std::string staticFile,
                                     size_t object)
    : staticFile_(std::move(staticFile)),
      object_(object),
      progress_(std::make_shared<std::atomic<double>>(0.0)) {
  // buildScene's stages in order; each reports its fraction.
  auto progress = [p = progress_](const char* stage, double fraction) {
    const double start = std::strcmp(stage, "load") == 0       ? 0.0
                         : std::strcmp(stage, "voxelize") == 0 ? 0.2
                                                               : 0.9;
    const double width = start == 0.0 ? 0.2 : start == 0.2 ? 0.7 : 0.1;
    p->store(start + width * fraction);
  };
  result_ =
      std::async(std::launch::async, [scene = std::move(scene), file = staticFile_, progress]() {
        return DynamicScene::prepare(scene, file, progress);
      });
}

BackgroundPrepare::~BackgroundPrepare() {
  if (result_.valid()) result_.wait();
}

std::optional<Result<DynamicScene::Prepared>> BackgroundPrepare::take(bool wait) {
  if (!result_.valid()) return std::nullopt;
  if (!wait && result_.wait_for(std::chrono::seconds(0)) != std::future_status::ready)
    return std::nullopt;
  return result_.get();
}

}  // namespace voxlink::viewer
